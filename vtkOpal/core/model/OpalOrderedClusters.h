// Which Voronoi cells are crystal (docs/design.md §2.9): correlated site
// percolation over the cells' adjacency graph, after Yokota & Fujishiro
// (2024), so ordered cells gather into patches instead of being strewn
// independently.
#pragma once

#include "OpalRandom.h"

#include <cstdint>
#include <vector>

namespace opal
{

// Each cell draws a uniform value; its score is the mean of the values over
// its closed neighbourhood (itself and its neighbours), so neighbouring
// scores correlate (about 0.5 for 3-D Voronoi cells, which share about a
// third of their neighbours); the round(fraction x the cells with voxels)
// highest-scoring cells with voxels are ordered (ties: the lower index).
// The ordered cells are the occupied sites of a correlated percolation:
// small fractions give isolated clumps, larger ones join into spanning
// patches. Returns 1 for an ordered cell; draws one value per cell from
// `random`, in cell order.
std::vector<std::uint8_t> orderedCells(const std::vector<std::vector<int>>& neighbours,
  const std::vector<std::uint8_t>& hasVoxels, double fraction, RandomSequence& random);

} // namespace opal
