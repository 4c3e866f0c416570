#include "OpalVolumeBuild.h"

#include "OpalMemory.h"
#include "OpalParallel.h"

#include <algorithm>

namespace opal
{

namespace
{
// Share of the work spent placing domains; filling the voxels takes the rest.
constexpr double LayoutShare = 0.1;

template <typename T>
T* dataOrNull(std::vector<T>& values)
{
  return values.empty() ? nullptr : values.data();
}

VolumeFields fieldsOf(BuiltVolume& volume)
{
  return { dataOrNull(volume.VoxelType), dataOrNull(volume.ParticleDiameter), dataOrNull(volume.Normal),
    volume.DomainId.data(), dataOrNull(volume.BraggLambdaMax), dataOrNull(volume.BraggLambdaMin),
    volume.ScatteringCoefficient.data(), volume.SurfaceDistance.data(), dataOrNull(volume.CellId),
    dataOrNull(volume.AbsorptionCoefficient), dataOrNull(volume.AbsorptionExponent),
    dataOrNull(volume.LatticeOrientation) };
}

void allocate(BuiltVolume& volume, bool absorbs, VolumeArrays arrays)
{
  const auto voxels = static_cast<std::size_t>(volume.VoxelGrid.voxelCount());
  if (arrays == VolumeArrays::All)
  {
    volume.VoxelType.resize(voxels);
    volume.ParticleDiameter.resize(voxels);
    volume.Normal.resize(3 * voxels);
    volume.LatticeOrientation.resize(4 * voxels);
    volume.BraggLambdaMax.resize(voxels);
    volume.BraggLambdaMin.resize(voxels);
  }
  volume.DomainId.resize(voxels);
  volume.ScatteringCoefficient.resize(voxels);
  volume.SurfaceDistance.resize(voxels);
  if (volume.Layout.hasCells() && arrays == VolumeArrays::All)
  {
    volume.CellId.resize(voxels);
  }
  if (absorbs)
  {
    volume.AbsorptionCoefficient.resize(voxels);
    volume.AbsorptionExponent.resize(voxels);
  }
}
} // namespace

RenderVolume BuiltVolume::renderVolume() const
{
  RenderVolume volume;
  volume.Dimensions = this->VoxelGrid.Dimensions;
  volume.Origin = this->VoxelGrid.Origin;
  volume.Spacing = this->VoxelGrid.Spacing;
  volume.ScatteringCoefficient = this->ScatteringCoefficient.data();
  volume.DomainId = this->DomainId.data();
  volume.SurfaceDistance = this->SurfaceDistance.data();
  if (!this->AbsorptionCoefficient.empty())
  {
    volume.AbsorptionCoefficient = this->AbsorptionCoefficient.data();
    volume.AbsorptionExponent = this->AbsorptionExponent.data();
  }
  volume.Domains = renderDomains(this->Layout);
  volume.SphereRefractiveIndex = this->SphereRefractiveIndex;
  volume.MatrixRefractiveIndex = this->MatrixRefractiveIndex;
  return volume;
}

std::string volumeMemoryError(const ModelParameters& parameters, VolumeArrays arrays, std::uint64_t pieceVoxels)
{
  const std::uint64_t gridVoxels = static_cast<std::uint64_t>(parameters.Dimensions[0]) *
    static_cast<std::uint64_t>(parameters.Dimensions[1]) * static_cast<std::uint64_t>(parameters.Dimensions[2]);
  const bool piece = pieceVoxels > 0 && pieceVoxels < gridVoxels;
  const std::uint64_t voxels = piece ? pieceVoxels : gridVoxels;
  // A Voronoi layout keeps the cells of the grid's voxels as runs
  // (voronoiCellRunBytes); the piece's CellId array, with every array, its
  // own voxels' (4 bytes).
  const bool voronoi = parameters.DomainLayout == DomainLayoutKind::Voronoi;
  const std::uint64_t absorptionBytes = parameters.absorbs() ? 4 + 4 : 0;
  const bool all = arrays == VolumeArrays::All;
  const std::uint64_t arrayBytes = all ? VolumeBytesPerVoxel : RenderVolumeBytesPerVoxel;
  const std::uint64_t needed = voxels * (arrayBytes + absorptionBytes + (voronoi && all ? 4 : 0)) +
    (voronoi ? voronoiCellRunBytes(parameters.Dimensions, parameters.VoronoiCellCount) : 0);
  const std::uint64_t available = physicalMemoryBytes();
  if (available == 0 || needed <= available)
  {
    return {};
  }
  const std::string dimensions = std::to_string(parameters.Dimensions[0]) + " x " +
    std::to_string(parameters.Dimensions[1]) + " x " + std::to_string(parameters.Dimensions[2]);
  return (piece ? "A piece of " + std::to_string(voxels) + " voxels of Dimensions " + dimensions + " needs"
                : "Dimensions " + dimensions + " need") +
    " about " + formatBytes(needed) + " for the volume's arrays, more than this machine's " +
    formatBytes(available) + " of memory.";
}

std::optional<BuiltVolume> buildVolume(
  const ModelParameters& parameters, const std::function<bool(double)>& progress, VolumeArrays arrays)
{
  auto report = [&progress](double fraction) { return !progress || progress(fraction); };
  BuiltVolume volume;
  volume.VoxelGrid = Grid::fromParameters(parameters);
  volume.SphereRefractiveIndex = parameters.SphereRefractiveIndex;
  volume.MatrixRefractiveIndex = parameters.MatrixRefractiveIndex;
  volume.Layout = DomainLayout::build(parameters, [&report](double f) { return report(LayoutShare * f); });
  if (volume.Layout.aborted())
  {
    return std::nullopt;
  }
  allocate(volume, parameters.absorbs(), arrays);
  const VolumeFiller filler(parameters, volume.Layout);
  const std::array<int, 3>& dims = volume.VoxelGrid.Dimensions;
  const std::array<int, 6> extent{ 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  const VolumeFields fields = fieldsOf(volume);
  // Slab by slab, reporting progress and honouring abort between slabs.
  const int chunk = std::max(1, dims[2] / 20);
  for (int k = 0; k < dims[2]; k += chunk)
  {
    const int kEnd = std::min(dims[2], k + chunk);
    parallelFor(k, kEnd, [&](int begin, int end) { filler.fill(extent, begin, end, fields); });
    if (!report(LayoutShare + (1 - LayoutShare) * kEnd / static_cast<double>(dims[2])))
    {
      return std::nullopt;
    }
  }
  return volume;
}

} // namespace opal
