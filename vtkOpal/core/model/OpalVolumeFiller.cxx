#include "OpalVolumeFiller.h"

#include "OpalOptics.h"

#include <algorithm>

namespace opal
{

VolumeFiller::VolumeFiller(const ModelParameters& parameters, const DomainLayout& layout)
  : Parameters(parameters)
  , Layout(layout)
  , VoxelGrid(Grid::fromParameters(parameters))
  , Shape(parameters.SemiAxes)
  , Diameters(parameters)
  , RayleighPerCubicNm(
      rayleighScatteringPerMm(1.0, parameters.ScatteringVolumeFraction, ReferenceWavelengthNm))
  , MaxSpacing(*std::max_element(this->VoxelGrid.Spacing.begin(), this->VoxelGrid.Spacing.end()))
{
  for (const Domain& domain : layout.domains())
  {
    const std::array<double, 4> q = latticeQuaternion(domain);
    this->Orientations.push_back({ static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2]),
      static_cast<float>(q[3]) });
  }
}

bool VolumeFiller::isSurfaceVoxel(int i, int j, int k) const
{
  static const int offsets[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
    { 0, 0, -1 } };
  for (const auto& o : offsets)
  {
    const int a = i + o[0], b = j + o[1], c = k + o[2];
    if (!this->VoxelGrid.contains(a, b, c) || !this->Shape.contains(this->VoxelGrid.position(a, b, c)))
    {
      return true;
    }
  }
  return false;
}

void VolumeFiller::fill(
  const std::array<int, 6>& extent, int kBegin, int kEnd, const VolumeFields& out) const
{
  for (int k = kBegin; k < kEnd; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      this->fillRow(extent, j, k, out);
    }
  }
}

void VolumeFiller::fillRow(const std::array<int, 6>& extent, int j, int k, const VolumeFields& out) const
{
  const Grid& grid = this->VoxelGrid;
  const std::int64_t nx = extent[1] - extent[0] + 1;
  const std::int64_t ny = extent[3] - extent[2] + 1;
  const std::int64_t rowStart = nx * ((j - extent[2]) + ny * (k - extent[4]));
  // The row's diffraction voxels, in increasing x (polygons; a Voronoi
  // voxel's domain is its cell's).
  auto domainVoxel = this->Layout.lowerBound(grid.linearIndex(extent[0], j, k));
  const auto domainEnd = this->Layout.voxels().end();
  const bool cells = this->Layout.hasCells();
  const VoronoiCellRuns::Run* run = cells ? this->Layout.cellRuns().runAt(extent[0], j, k) : nullptr;
  const VoronoiCellRuns::Run* rowEnd = cells ? this->Layout.cellRuns().rowEnd(j, k) : nullptr;
  for (int i = extent[0]; i <= extent[1]; ++i)
  {
    const std::int64_t o = rowStart + (i - extent[0]);
    const std::int64_t globalIndex = grid.linearIndex(i, j, k);
    // The shape is symmetric in x: evaluate the distance at the canonical
    // voxel of each mirror pair (so every piece gets identical values) and
    // reuse the mirror's value when this row already holds it.
    const int mirror = grid.Dimensions[0] - 1 - i;
    const double distance = mirror < i && mirror >= extent[0]
      ? static_cast<double>(out.SurfaceDistance[o - (i - mirror)])
      : this->Shape.signedDistance(grid.position(std::min(i, mirror), j, k));
    out.SurfaceDistance[o] = static_cast<float>(distance);
    clearVoxel(o, out);
    while (cells && run + 1 != rowEnd && run[1].FirstX <= i)
    {
      ++run;
    }
    if (out.CellId)
    {
      out.CellId[o] = run->Cell;
    }
    while (domainVoxel != domainEnd && domainVoxel->Index < globalIndex)
    {
      ++domainVoxel;
    }
    const int domain = cells ? this->Layout.cellDomain(run->Cell)
      : domainVoxel != domainEnd && domainVoxel->Index == globalIndex ? domainVoxel->DomainId
                                                                      : -1;
    if (domain >= 0)
    {
      this->fillDiffractionVoxel(o, this->Layout.domains()[static_cast<std::size_t>(domain)], out);
      this->fillAbsorption(o, j, out);
    }
    else if (this->Shape.contains(grid.position(i, j, k)))
    {
      this->fillScatteringVoxel(o, { i, j, k }, distance, out);
      this->fillAbsorption(o, j, out);
    }
    else if (out.VoxelType)
    {
      out.VoxelType[o] = EmptyVoxel;
    }
  }
}

void VolumeFiller::clearVoxel(std::int64_t o, const VolumeFields& out)
{
  out.DomainId[o] = -1;
  out.ScatteringCoefficient[o] = 0.0f;
  if (out.VoxelType)
  {
    float* normal = out.Normal + 3 * o;
    normal[0] = normal[1] = normal[2] = 0.0f;
    out.BraggLambdaMax[o] = 0.0f;
    out.BraggLambdaMin[o] = 0.0f;
    out.ParticleDiameter[o] = 0.0f;
  }
  if (out.LatticeOrientation)
  {
    std::fill_n(out.LatticeOrientation + 4 * o, 4, 0.0f);
  }
  if (out.AbsorptionCoefficient)
  {
    out.AbsorptionCoefficient[o] = 0.0f;
    out.AbsorptionExponent[o] = 0.0f;
  }
}

// Absorption of a voxel of the opal (docs/design.md §2.10): the backing's,
// grey, below BackingThickness; the body's above, domains included (their
// spheres are the body's silica).
void VolumeFiller::fillAbsorption(std::int64_t o, int j, const VolumeFields& out) const
{
  if (!out.AbsorptionCoefficient)
  {
    return;
  }
  const bool backing = this->VoxelGrid.position(0, j, 0)[1] < this->Parameters.BackingThickness;
  out.AbsorptionCoefficient[o] =
    static_cast<float>(backing ? this->Parameters.BackingAbsorption : this->Parameters.BodyAbsorption);
  out.AbsorptionExponent[o] = backing ? 0.0f : static_cast<float>(this->Parameters.BodyAbsorptionExponent);
}

// Diffraction voxel: FCC (111) planes; no scattering in the paper (§6.2),
// DomainScatteringCoefficient beyond it (docs/design.md §2.10).
void VolumeFiller::fillDiffractionVoxel(std::int64_t o, const Domain& domain, const VolumeFields& out) const
{
  out.DomainId[o] = domain.Id;
  out.ScatteringCoefficient[o] = static_cast<float>(this->Parameters.DomainScatteringCoefficient);
  if (out.VoxelType)
  {
    const double mu = this->Parameters.RefractiveIndex;
    const double lambdaMax = braggLambdaMax(domain.ParticleDiameter, mu);
    out.VoxelType[o] = DiffractionVoxel;
    out.ParticleDiameter[o] = static_cast<float>(domain.ParticleDiameter);
    out.BraggLambdaMax[o] = static_cast<float>(lambdaMax);
    out.BraggLambdaMin[o] = static_cast<float>(braggLambdaMin(lambdaMax, mu));
    for (std::size_t a = 0; a < 3; ++a)
    {
      out.Normal[3 * o + static_cast<std::int64_t>(a)] = static_cast<float>(domain.Normal[a]);
    }
  }
  if (out.LatticeOrientation)
  {
    const std::array<float, 4>& q = this->Orientations[static_cast<std::size_t>(domain.Id)];
    std::copy(q.begin(), q.end(), out.LatticeOrientation + 4 * o);
  }
}

void VolumeFiller::fillScatteringVoxel(
  std::int64_t o, const std::array<int, 3>& ijk, double distance, const VolumeFields& out) const
{
  const double diameter = this->Diameters.at(ijk[0], ijk[1], ijk[2]);
  out.ScatteringCoefficient[o] = static_cast<float>(this->RayleighPerCubicNm * diameter * diameter * diameter);
  if (!out.VoxelType)
  {
    return;
  }
  out.VoxelType[o] = ScatteringVoxel;
  out.ParticleDiameter[o] = static_cast<float>(diameter);
  // Only voxels within one spacing of the surface can have an empty
  // neighbour; the margin keeps float rounding of reused distances moot.
  if (distance >= -1.5 * this->MaxSpacing && this->isSurfaceVoxel(ijk[0], ijk[1], ijk[2]))
  {
    const std::array<double, 3> n = this->Shape.outwardNormal(this->VoxelGrid.position(ijk[0], ijk[1], ijk[2]));
    for (std::size_t a = 0; a < 3; ++a)
    {
      out.Normal[3 * o + static_cast<std::int64_t>(a)] = static_cast<float>(n[a]);
    }
  }
}

} // namespace opal
