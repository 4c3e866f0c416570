// The whole volume built in memory (docs/design.md §2), for the programs and
// the benches: the domain layout, then every voxel's fields, in parallel.
// The VTK source fills its own arrays over an update extent with the same
// DomainLayout and VolumeFiller, so both give the same values.
#pragma once

#include "OpalDomainLayout.h"
#include "OpalGrid.h"
#include "OpalModelParameters.h"
#include "OpalRenderVolume.h"
#include "OpalVolumeFiller.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace opal
{

// Which arrays a build fills: all of them (the volume's description, as the
// VTK source gives), or only what the render reads (ScatteringCoefficient,
// DomainId, SurfaceDistance, the absorption and the domain table): 41 bytes
// per voxel less, and no surface normals to compute.
enum class VolumeArrays
{
  All,
  Render,
};

struct BuiltVolume
{
  Grid VoxelGrid;
  DomainLayout Layout;
  std::vector<std::uint8_t> VoxelType; // this and the next five: empty for VolumeArrays::Render
  std::vector<float> ParticleDiameter, Normal, BraggLambdaMax, BraggLambdaMin, ScatteringCoefficient, SurfaceDistance;
  std::vector<std::int32_t> DomainId;
  std::vector<std::int32_t> CellId; // Voronoi layout only, else empty
  std::vector<float> AbsorptionCoefficient, AbsorptionExponent; // only if the model absorbs, else empty
  std::vector<float> LatticeOrientation;                        // 4 per voxel (w, x, y, z)
  double SphereRefractiveIndex = 1.45, MatrixRefractiveIndex = 1.33; // the model's crystal (§7.2)

  // The render's view of it (pointers into this object's arrays).
  RenderVolume renderVolume() const;
};

// Empty if the volume's arrays fit in this machine's memory, else the
// sentence refusing it with the estimate (checked before any work): those of
// the whole grid, or of a piece of `voxels` voxels.
std::string volumeMemoryError(
  const ModelParameters& parameters, VolumeArrays arrays = VolumeArrays::All, std::uint64_t voxels = 0);

// Builds the volume of valid parameters; progress(fraction) may return false
// to abort, and then the result is empty.
std::optional<BuiltVolume> buildVolume(const ModelParameters& parameters,
  const std::function<bool(double)>& progress = nullptr, VolumeArrays arrays = VolumeArrays::All);

} // namespace opal
