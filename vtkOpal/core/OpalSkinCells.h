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

struct SkinExtendedFields
{
  std::vector<float> ScatteringCoefficient;
  std::vector<std::int32_t> DomainId;
};

// The volume's two coefficient fields with every skin cell filled: cells
// within one cell diagonal outside the surface (the surface is the zero of
// trilinear SurfaceDistance, which can run a little outside the exact
// distance's), ScatteringCoefficient 0 and DomainId -1, and a neighbour with
// SurfaceDistance <= 0; the neighbour with the smallest SurfaceDistance
// wins (the first in z, y, x order on a tie).
SkinExtendedFields extendIntoSkin(const RenderVolume& volume);

} // namespace opal
