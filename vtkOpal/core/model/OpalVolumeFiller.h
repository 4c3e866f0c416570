// Fills the model's per-voxel fields (docs/design.md §2) over any sub-extent of
// the grid. Every value derives from the global voxel index, the parameters
// and the domain layout, so pieces agree exactly with the whole volume.
#pragma once

#include "OpalDiameterField.h"
#include "OpalDomainLayout.h"
#include "OpalGrid.h"
#include "OpalHalfEllipsoid.h"
#include "OpalModelParameters.h"

#include <array>
#include <cstdint>
#include <vector>

namespace opal
{

enum VoxelType : std::uint8_t
{
  EmptyVoxel = 0,
  ScatteringVoxel = 1,
  DiffractionVoxel = 2,
};

// Destination arrays, each laid out over the extent with x fastest. The
// description (VoxelType, ParticleDiameter, Normal, BraggLambdaMax/Min) is
// written only where VoxelType is given: a render reads none of it.
struct VolumeFields
{
  std::uint8_t* VoxelType;      // null: no description written
  float* ParticleDiameter;      // nm
  float* Normal;                // 3 components
  std::int32_t* DomainId;
  float* BraggLambdaMax;        // nm
  float* BraggLambdaMin;        // nm
  float* ScatteringCoefficient; // 1/mm at 550 nm
  float* SurfaceDistance;       // mm, negative inside
  std::int32_t* CellId = nullptr; // the Voronoi cell (-1 outside the opal); only with a Voronoi layout
  // Only when the model absorbs (ModelParameters::absorbs, docs/design.md §2.10):
  float* AbsorptionCoefficient = nullptr; // 1/mm at 550 nm
  float* AbsorptionExponent = nullptr;    // p of the voxel's mu_a(lambda) = mu_a(550) (550/lambda)^p
  // 4 components (w, x, y, z): the domain's lattice orientation, 0 outside
  // domains (docs/design.md §2.5); null: not written.
  float* LatticeOrientation = nullptr;
};

class VolumeFiller
{
public:
  VolumeFiller(const ModelParameters& parameters, const DomainLayout& layout);

  // Fills the voxels of `extent` (inclusive index bounds i0 i1 j0 j1 k0 k1)
  // whose z index lies in [kBegin, kEnd). Thread-safe for disjoint ranges.
  void fill(const std::array<int, 6>& extent, int kBegin, int kEnd, const VolumeFields& out) const;

private:
  bool isSurfaceVoxel(int i, int j, int k) const;
  void fillRow(const std::array<int, 6>& extent, int j, int k, const VolumeFields& out) const;
  static void clearVoxel(std::int64_t o, const VolumeFields& out);
  void fillDiffractionVoxel(std::int64_t o, const Domain& domain, const VolumeFields& out) const;
  void fillAbsorption(std::int64_t o, int j, const VolumeFields& out) const;
  void fillScatteringVoxel(std::int64_t o, const std::array<int, 3>& ijk, double distance, const VolumeFields& out) const;

  ModelParameters Parameters;
  const DomainLayout& Layout;
  Grid VoxelGrid;
  HalfEllipsoid Shape;
  DiameterField Diameters;
  double RayleighPerCubicNm; // mu_s(550) / l^3: eq. 1 with n = 6 phi / (pi l^3)
  double MaxSpacing;
  std::vector<std::array<float, 4>> Orientations; // latticeQuaternion of each domain
};

} // namespace opal
