// The scattering spheres' diameter per voxel (docs/design.md §2.3): the
// paper's independent uniform draw per voxel, or, with a correlation length
// L > 0, a smooth random field: value noise whose lattice (spacing L, anchored
// at the grid box's corner) carries independent uniform values, interpolated
// trilinearly. Its autocorrelation at a lag s L along an axis is
// (2/3 - s^2 + s^3/2) / (2/3) for s <= 1 (0.25 at L) and 0 beyond 2 L; its
// mean is the range's middle. Both are counter-based: any piece gets the
// whole run's values.
#pragma once

#include "OpalGrid.h"
#include "OpalModelParameters.h"

#include <array>
#include <cstdint>

namespace opal
{

class DiameterField
{
public:
  explicit DiameterField(const ModelParameters& parameters);

  // Diameter (nm) of the scattering voxel (i, j, k).
  double at(int i, int j, int k) const;

  // The field's unit value in [0, 1] at a position (mm): the independent
  // voxel draw when the correlation length is 0 (position ignored, the
  // voxel's global index used), else the value noise. Exposed for tests.
  double unitValue(const std::array<double, 3>& position, std::int64_t globalIndex) const;

private:
  double latticeValue(std::int64_t ix, std::int64_t iy, std::int64_t iz) const;

  std::uint32_t Seed;
  std::array<double, 2> Range;
  double CorrelationLength;
  Grid VoxelGrid;
  std::array<double, 3> Corner; // the grid box's lower corner, the lattice's node (0, 0, 0)
};

} // namespace opal
