// SurfaceDistance as the highlight pass reads it (docs/design.md §3.4, "The
// highlight's surface by tiles"): the grid's cells in tiles of `Cells`^3,
// each tile either held exact (the SurfaceDistance of its (Cells + 1)^3
// voxels, so that a trilinear read within it reads the very values of the
// field) or, where the surface is not near, one value: a bound of
// SurfaceDistance over the tile with its sign. The highlight's traces need
// no more: sphere tracing steps by a bound, the sign is the inside, and the
// bisection and the normal read near the surface, in the held tiles. Small
// beside the field (26% of its bytes at 320 x 160 x 400, falling as 1 / resolution),
// every process can hold it whole while the field itself is held by piece
// (docs/design.md §8.1).
#pragma once

#include "OpalRenderVolume.h"

#include <array>
#include <cstdint>
#include <vector>

namespace opal
{

// A tile is held exact where its SurfaceDistance comes within this many of
// the grid's largest spacing of 0: the normal's reads lie a spacing from the
// surface, where a distance is at most a spacing.
constexpr double SurfaceTileNearSpacings = 2.0;

struct SurfaceTiles
{
  int Cells = 0;                  // cells per tile axis; a held tile's voxels per axis are Cells + 1
  std::array<int, 3> Count{};     // tiles per axis, x fastest
  std::vector<std::int32_t> Slot; // per tile: its values' slot in Values, or -1 where Bound alone stands for it
  // Per tile where Slot is -1: the least |SurfaceDistance| the trilinear
  // read gives anywhere in the tile's cells (and beyond the outermost
  // centres up to the grid's box, where the read continues linearly), with
  // the tile's one sign; 0 where held.
  std::vector<float> Bound;
  std::vector<float> Values; // (Cells + 1)^3 per held tile, x fastest

  std::size_t tileCount() const { return this->Slot.size(); }
  std::size_t heldTiles() const;
  std::size_t bytes() const;
};

// The tiles per axis of a grid of `dimensions` voxels: its cells (the
// voxels less one, at least one) over `cells`, rounded up.
std::array<int, 3> surfaceTileCount(const std::array<int, 3>& dimensions, int cells);

// The tiles of `volume`'s SurfaceDistance, of `cells`^3 cells (cells >= 1).
SurfaceTiles surfaceTiles(const RenderVolume& volume, int cells);

} // namespace opal
