// The skin of the stone (docs/design.md §3.3): the voxel cells whose centre
// lies outside the smooth surface (SurfaceDistance > 0) although the surface
// may cut them. The model leaves them empty (a voxel staircase), but the
// render's medium is the smooth surface's inside: both the view and the light
// path clip there, so a skin cell with no coefficient of its own takes the
// ScatteringCoefficient and DomainId of its deepest inside neighbour (of 26).
// The body then reaches the smooth surface everywhere, and the light field
// has no sub-voxel gap under it that trilinear reads could not resolve.
#pragma once

#include "OpalRenderVolume.h"

#include <cstdint>
#include <vector>

namespace opal
{

// A skin cell and the inside voxel whose coefficients it takes.
struct SkinCell
{
  std::int64_t Index;
  std::int64_t Source;
};

// The volume's skin cells to fill: cells within one cell diagonal outside
// the surface (the surface is the zero of trilinear SurfaceDistance, which
// can run a little outside the exact distance's), ScatteringCoefficient 0 and
// DomainId -1, with a neighbour of SurfaceDistance <= 0; the neighbour with
// the smallest SurfaceDistance is the source (the first in z, y, x order on a
// tie). Sources lie inside, so no source is itself a skin cell. Few: the
// caller applies them to its copy of the fields. Those of layers z
// [first, end) alone, whose medium and the layer beside them the volume
// holds (RenderVolume::mediumLayers: a process of a march shared by
// processes holds its piece's, docs/design.md §8.1).
std::vector<SkinCell> skinCells(const RenderVolume& volume, std::pair<int, int> layers);

} // namespace opal
