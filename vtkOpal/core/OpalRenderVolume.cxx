#include "OpalRenderVolume.h"

#include "OpalDomainLayout.h"
#include "OpalOptics.h"

namespace opal
{

std::size_t RenderVolume::voxelCount() const
{
  return static_cast<std::size_t>(this->Dimensions[0]) * static_cast<std::size_t>(this->Dimensions[1]) *
    static_cast<std::size_t>(this->Dimensions[2]);
}

RenderDomain renderDomain(const std::array<double, 3>& normal, double particleDiameter)
{
  RenderDomain domain;
  for (std::size_t a = 0; a < 3; ++a)
  {
    domain.LatticeNormal[a] = static_cast<float>(normal[a]);
  }
  domain.PlaneSpacing = static_cast<float>(fccPlaneSpacing(static_cast<float>(particleDiameter)));
  return domain;
}

std::vector<RenderDomain> renderDomains(const DomainLayout& layout)
{
  std::vector<RenderDomain> table(layout.domains().size());
  for (const Domain& domain : layout.domains())
  {
    table[static_cast<std::size_t>(domain.Id)] = renderDomain(domain.Normal, domain.ParticleDiameter);
  }
  return table;
}

std::string validate(const RenderVolume& volume)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (volume.Dimensions[a] < 1 || !(volume.Spacing[a] > 0))
    {
      return "The input volume needs positive dimensions and spacing.";
    }
  }
  if (!volume.ScatteringCoefficient || !volume.DomainId || !volume.SurfaceDistance)
  {
    return "The input volume lacks ScatteringCoefficient, DomainId or SurfaceDistance.";
  }
  const std::int64_t domains = static_cast<std::int64_t>(volume.Domains.size());
  for (std::size_t i = 0; i < volume.voxelCount(); ++i)
  {
    if (volume.DomainId[i] < -1 || volume.DomainId[i] >= domains)
    {
      return "DomainId " + std::to_string(volume.DomainId[i]) + " at voxel " + std::to_string(i) +
        " is outside the domain table (" + std::to_string(domains) + " domains).";
    }
  }
  return {};
}

} // namespace opal
