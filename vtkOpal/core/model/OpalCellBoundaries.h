// The surfaces of a Voronoi layout's ordered cells (docs/design.md §2.9), for
// the source's second output: every voxel face where an ordered cell meets
// another cell or the outside, as a quadrilateral facing out of the cell.
// Corners are shared (a watertight mesh per cell), so ParaView shades and
// clips it as one surface.
#pragma once

#include "OpalDomainLayout.h"
#include "OpalGrid.h"

#include <array>
#include <vector>

namespace opal
{

struct CellBoundaryMesh
{
  std::vector<std::array<double, 3>> Points; // mm, voxel corners
  std::vector<std::array<int, 4>> Faces;     // point indices, counter-clockwise seen from outside the cell
  std::vector<int> FaceDomain;               // the ordered cell's domain
};

// Empty unless the layout has cells.
CellBoundaryMesh orderedCellBoundaries(const Grid& grid, const DomainLayout& layout);

} // namespace opal
