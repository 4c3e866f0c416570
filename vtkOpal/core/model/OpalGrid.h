// The voxel grid of the model: voxel centres are the image's points and the
// box [-X/2, X/2] x [0, Y] x [-Z/2, Z/2] mm is exactly covered (docs/design.md §2.1).
#pragma once

#include "OpalModelParameters.h"

#include <array>
#include <cmath>
#include <cstdint>

namespace opal
{

struct Grid
{
  std::array<int, 3> Dimensions{};
  std::array<double, 3> Spacing{};
  std::array<double, 3> Origin{}; // centre of voxel (0, 0, 0)

  static Grid fromParameters(const ModelParameters& p)
  {
    Grid grid;
    grid.Dimensions = p.Dimensions;
    for (int a = 0; a < 3; ++a)
    {
      grid.Spacing[a] = p.PhysicalSize[a] / p.Dimensions[a];
    }
    grid.Origin = { -p.PhysicalSize[0] / 2 + grid.Spacing[0] / 2, grid.Spacing[1] / 2,
      -p.PhysicalSize[2] / 2 + grid.Spacing[2] / 2 };
    return grid;
  }

  double coordinate(int axis, int index) const { return this->Origin[axis] + index * this->Spacing[axis]; }

  std::array<double, 3> position(int i, int j, int k) const
  {
    return { this->coordinate(0, i), this->coordinate(1, j), this->coordinate(2, k) };
  }

  // Index of the voxel containing coordinate c along an axis (may be outside [0, dim)).
  int voxelIndex(int axis, double c) const
  {
    return static_cast<int>(std::floor((c - this->Origin[axis]) / this->Spacing[axis] + 0.5));
  }

  bool contains(int i, int j, int k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < this->Dimensions[0] && j < this->Dimensions[1] &&
      k < this->Dimensions[2];
  }

  // Global linear index, x fastest (VTK's point order).
  std::int64_t linearIndex(int i, int j, int k) const
  {
    return i + static_cast<std::int64_t>(this->Dimensions[0]) *
      (j + static_cast<std::int64_t>(this->Dimensions[1]) * k);
  }

  std::int64_t voxelCount() const
  {
    return static_cast<std::int64_t>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
};

} // namespace opal
