#include "OpalRenderVolume.h"

#include "OpalCoupledWave.h"
#include "OpalDomainLayout.h"
#include "OpalOptics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace opal
{

std::size_t RenderVolume::voxelCount() const
{
  return static_cast<std::size_t>(this->Dimensions[0]) * static_cast<std::size_t>(this->Dimensions[1]) *
    static_cast<std::size_t>(this->Dimensions[2]);
}

std::size_t RenderVolume::layerVoxels() const
{
  return static_cast<std::size_t>(this->Dimensions[0]) * static_cast<std::size_t>(this->Dimensions[1]);
}

std::pair<int, int> RenderVolume::mediumLayers() const
{
  return this->Held ? this->Held->Layers : std::make_pair(0, this->Dimensions[2]);
}

std::pair<std::size_t, std::size_t> RenderVolume::voxelsOfLayers(std::pair<int, int> layers) const
{
  return { this->layerVoxels() * static_cast<std::size_t>(layers.first),
    this->layerVoxels() * static_cast<std::size_t>(layers.second) };
}

std::size_t RenderVolume::mediumFirstVoxel() const
{
  return this->voxelsOfLayers(this->mediumLayers()).first;
}

bool RenderVolume::absorbs() const
{
  if (this->Held)
  {
    return this->Held->Whole.Absorbs;
  }
  return this->AbsorptionCoefficient &&
    std::any_of(this->AbsorptionCoefficient, this->AbsorptionCoefficient + this->voxelCount(),
      [](float absorption) { return absorption > 0.0f; });
}

float RenderVolume::colouredAbsorptionExponent() const
{
  if (this->Held)
  {
    return this->Held->Whole.ColouredAbsorptionExponent;
  }
  for (std::size_t i = 0; this->AbsorptionCoefficient && i < this->voxelCount(); ++i)
  {
    if (this->AbsorptionCoefficient[i] > 0.0f && this->AbsorptionExponent[i] != 0.0f)
    {
      return this->AbsorptionExponent[i];
    }
  }
  return 0.0f;
}

std::vector<std::array<double, 3>> RenderVolume::domainCentres() const
{
  const MediumSums sums = this->Held ? this->Held->Whole : sumMedium(*this, this->mediumLayers());
  const std::array<int, 3>& n = this->Dimensions;
  std::vector<std::array<double, 3>> centres(this->Domains.size());
  for (std::size_t d = 0; d < centres.size(); ++d)
  {
    const std::uint64_t count = d < sums.DomainVoxels.size() ? sums.DomainVoxels[d] : 0;
    for (std::size_t a = 0; a < 3; ++a)
    {
      const double index = count > 0 ? sums.DomainIndexSums[d][a] / static_cast<double>(count) : 0.5 * (n[a] - 1);
      centres[d][a] = this->Origin[a] + index * this->Spacing[a];
    }
  }
  return centres;
}

void MediumSums::add(const MediumSums& later)
{
  this->Absorbs = this->Absorbs || later.Absorbs;
  if (this->ColouredAbsorptionExponent == 0.0f)
  {
    this->ColouredAbsorptionExponent = later.ColouredAbsorptionExponent;
  }
  this->DomainIndexSums.resize(std::max(this->DomainIndexSums.size(), later.DomainIndexSums.size()));
  this->DomainVoxels.resize(this->DomainIndexSums.size());
  for (std::size_t d = 0; d < later.DomainVoxels.size(); ++d)
  {
    for (std::size_t a = 0; a < 3; ++a)
    {
      this->DomainIndexSums[d][a] += later.DomainIndexSums[d][a];
    }
    this->DomainVoxels[d] += later.DomainVoxels[d];
  }
}

MediumSums sumMedium(const RenderVolume& volume, std::pair<int, int> layers)
{
  MediumSums sums;
  sums.DomainIndexSums.assign(volume.Domains.size(), std::array<double, 3>{});
  sums.DomainVoxels.assign(volume.Domains.size(), 0);
  const std::size_t first = volume.mediumFirstVoxel(), layer = volume.layerVoxels();
  const auto [begin, end] = volume.voxelsOfLayers(layers);
  const auto nx = static_cast<std::size_t>(volume.Dimensions[0]);
  for (std::size_t i = begin; i < end; ++i)
  {
    const std::size_t held = i - first;
    if (volume.AbsorptionCoefficient && volume.AbsorptionCoefficient[held] > 0.0f)
    {
      sums.Absorbs = true;
      const float exponent = volume.AbsorptionExponent[held];
      sums.ColouredAbsorptionExponent = sums.ColouredAbsorptionExponent == 0.0f ? exponent : sums.ColouredAbsorptionExponent;
    }
    const std::int32_t domain = volume.DomainId[held];
    if (domain < 0 || static_cast<std::size_t>(domain) >= volume.Domains.size())
    {
      continue;
    }
    const std::array<std::size_t, 3> index{ i % nx, i % layer / nx, i / layer };
    for (std::size_t a = 0; a < 3; ++a)
    {
      sums.DomainIndexSums[static_cast<std::size_t>(domain)][a] += static_cast<double>(index[a]);
    }
    ++sums.DomainVoxels[static_cast<std::size_t>(domain)];
  }
  return sums;
}

RenderDomain renderDomain(
  const std::array<double, 3>& normal, double particleDiameter, const std::array<double, 4>& orientation)
{
  RenderDomain domain;
  for (std::size_t a = 0; a < 3; ++a)
  {
    domain.LatticeNormal[a] = static_cast<float>(normal[a]);
  }
  for (std::size_t a = 0; a < 4; ++a)
  {
    domain.Orientation[a] = static_cast<float>(orientation[a]);
  }
  domain.PlaneSpacing = static_cast<float>(fccPlaneSpacing(static_cast<float>(particleDiameter)));
  return domain;
}

std::vector<RenderDomain> renderDomains(const DomainLayout& layout)
{
  std::vector<RenderDomain> table(layout.domains().size());
  for (const Domain& domain : layout.domains())
  {
    table[static_cast<std::size_t>(domain.Id)] = renderDomain(domain.Normal, domain.ParticleDiameter, latticeQuaternion(domain));
  }
  return table;
}

namespace
{
// The first voxel whose ScatteringCoefficient is not a finite value >= 0, or
// whose SurfaceDistance is not finite, named; empty if none.
std::string checkVoxelValues(const RenderVolume& volume)
{
  const auto [begin, end] = volume.voxelsOfLayers(volume.mediumLayers());
  for (std::size_t i = begin; i < end; ++i)
  {
    const float mus = volume.ScatteringCoefficient[i - begin];
    if (!std::isfinite(mus) || mus < 0.0f)
    {
      return "ScatteringCoefficient " + std::to_string(mus) + " at voxel " + std::to_string(i) +
        " is not a finite value >= 0 (1/mm).";
    }
  }
  for (std::size_t i = 0; i < volume.voxelCount(); ++i)
  {
    if (!std::isfinite(volume.SurfaceDistance[i]))
    {
      return "SurfaceDistance at voxel " + std::to_string(i) + " is not finite.";
    }
  }
  return {};
}

// AbsorptionCoefficient finite and >= 0, AbsorptionExponent finite, and the
// absorbing voxels' exponents 0 or one other value; empty if so.
std::string checkAbsorption(const RenderVolume& volume)
{
  if (!volume.AbsorptionCoefficient)
  {
    return {};
  }
  const float coloured = volume.colouredAbsorptionExponent();
  const auto [begin, end] = volume.voxelsOfLayers(volume.mediumLayers());
  for (std::size_t i = begin; i < end; ++i)
  {
    const float absorption = volume.AbsorptionCoefficient[i - begin], exponent = volume.AbsorptionExponent[i - begin];
    if (!std::isfinite(absorption) || absorption < 0.0f)
    {
      return "AbsorptionCoefficient " + std::to_string(absorption) + " at voxel " + std::to_string(i) +
        " is not a finite value >= 0 (1/mm).";
    }
    if (!std::isfinite(exponent))
    {
      return "AbsorptionExponent at voxel " + std::to_string(i) + " is not finite.";
    }
    if (absorption > 0.0f && exponent != 0.0f && exponent != coloured)
    {
      return "AbsorptionExponent " + std::to_string(exponent) + " at voxel " + std::to_string(i) +
        " differs from " + std::to_string(coloured) + " elsewhere: the render takes one exponent besides 0 (grey).";
    }
  }
  return {};
}

// A medium held by layers: within the grid, its sums one per domain.
std::string checkHeldMedium(const RenderVolume& volume)
{
  if (!volume.Held)
  {
    return {};
  }
  const auto [first, end] = volume.Held->Layers;
  if (first < 0 || end > volume.Dimensions[2] || first >= end)
  {
    return "The medium held by layers (" + std::to_string(first) + " to " + std::to_string(end) +
      ") is not a range of the volume's " + std::to_string(volume.Dimensions[2]) + " layers z.";
  }
  const MediumSums& whole = volume.Held->Whole;
  if (whole.DomainVoxels.size() != volume.Domains.size() || whole.DomainIndexSums.size() != volume.Domains.size())
  {
    return "The whole medium's sums of a medium held by layers give " + std::to_string(whole.DomainVoxels.size()) +
      " domains, not the table's " + std::to_string(volume.Domains.size()) + ".";
  }
  return {};
}

// Every DomainId -1 or within the table, every domain a finite unit-ish
// normal and a positive finite plane spacing; empty if so.
std::string checkDomains(const RenderVolume& volume)
{
  const auto domains = static_cast<std::int64_t>(volume.Domains.size());
  const auto [begin, end] = volume.voxelsOfLayers(volume.mediumLayers());
  for (std::size_t i = begin; i < end; ++i)
  {
    const std::int32_t domain = volume.DomainId[i - begin];
    if (domain < -1 || domain >= domains)
    {
      return "DomainId " + std::to_string(domain) + " at voxel " + std::to_string(i) +
        " is outside the domain table (" + std::to_string(domains) + " domains).";
    }
  }
  for (std::size_t d = 0; d < volume.Domains.size(); ++d)
  {
    const auto& n = volume.Domains[d].LatticeNormal;
    const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const float spacing = volume.Domains[d].PlaneSpacing;
    if (!std::isfinite(length) || !(length > 0.5f && length < 2.0f) || !std::isfinite(spacing) || !(spacing > 0.0f))
    {
      return "Domain " + std::to_string(d) + " of the domain table needs a finite unit DomainNormal and a positive "
        "DomainParticleDiameter.";
    }
    const auto& q = volume.Domains[d].Orientation;
    const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!std::isfinite(norm) || !(norm > 0.99f && norm < 1.01f))
    {
      return "Domain " + std::to_string(d) + " of the domain table needs a finite unit DomainOrientation.";
    }
  }
  return {};
}

} // namespace

std::string validate(const RenderVolume& volume)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (volume.Dimensions[a] < 1 || !(volume.Spacing[a] > 0) || !std::isfinite(volume.Spacing[a]) ||
      !std::isfinite(volume.Origin[a]))
    {
      return "The input volume needs positive dimensions and a finite origin and positive spacing.";
    }
  }
  if (volume.voxelCount() > MostRenderedVoxels)
  {
    return "The input volume has " + std::to_string(volume.voxelCount()) + " voxels; the render reads at most " +
      std::to_string(MostRenderedVoxels) + " (2^32 - 1, a voxel's index on the device): use fewer voxels.";
  }
  const auto layerVoxels = static_cast<std::uint64_t>(volume.Dimensions[0]) * static_cast<std::uint64_t>(volume.Dimensions[2]);
  if (layerVoxels > MostLayerVoxels)
  {
    return "The input volume's layers y hold " + std::to_string(layerVoxels) + " voxels each (x by z); the render reads at most " +
      std::to_string(MostLayerVoxels) + " (2^31 - 1, the light's sweep of a layer): use fewer voxels in x and z.";
  }
  if (!volume.ScatteringCoefficient || !volume.DomainId || !volume.SurfaceDistance)
  {
    return "The input volume lacks ScatteringCoefficient, DomainId or SurfaceDistance.";
  }
  if (!volume.AbsorptionCoefficient != !volume.AbsorptionExponent)
  {
    return "The input volume has one of AbsorptionCoefficient and AbsorptionExponent without the other.";
  }
  const ColloidalCrystal crystal{ volume.SphereRefractiveIndex, volume.MatrixRefractiveIndex };
  const std::string held = checkHeldMedium(volume);
  if (!held.empty())
  {
    return held;
  }
  for (const std::string& error : { checkVoxelValues(volume), checkAbsorption(volume), crystalError(crystal) })
  {
    if (!error.empty())
    {
      return error;
    }
  }
  return checkDomains(volume);
}

} // namespace opal
