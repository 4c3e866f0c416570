// Which Voronoi cells are crystal (docs/design.md §2.6): clusters grown by
// site percolation over the cells' adjacency graph, as in Yokota & Fujishiro
// (2024), so ordered cells gather into patches instead of being strewn
// independently.
#pragma once

#include "OpalRandom.h"

#include <cstdint>
#include <vector>

namespace opal
{

// Leath's growth of site-percolation clusters with occupation probability
// `fraction`: a random cell not yet ordered seeds a cluster; each neighbour of
// a cluster cell is tested once per cluster and joins with that probability;
// when a cluster stops growing, the next seed follows, until
// round(fraction x the cells with voxels) cells are ordered. Returns 1 for an
// ordered cell. Below the graph's percolation threshold (~0.15 for 3-D
// Voronoi cells) the clusters stay small specks; above it they spread into
// large connected patches. Draws from `random` in order.
std::vector<std::uint8_t> growOrderedClusters(const std::vector<std::vector<int>>& neighbours,
  const std::vector<std::uint8_t>& hasVoxels, double fraction, RandomSequence& random);

} // namespace opal
