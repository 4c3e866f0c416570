// Additively weighted Voronoi cells (Yokota & Fujishiro 2024; docs/design.md
// §2.9): sites drawn in the opal, each with a weight w_i, and each point
// belongs to the cell minimising |x - s_i| - w_i. The search buckets the sites
// on a uniform grid and lists, per bucket, the sites that can be nearest to
// some point of it, so a voxel tests a handful of sites instead of all.
#pragma once

#include "OpalGrid.h"
#include "OpalHalfEllipsoid.h"
#include "OpalModelParameters.h"
#include "OpalRandom.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace opal
{

struct VoronoiSite
{
  std::array<double, 3> Position{}; // mm, inside the opal
  double Weight = 0;                // mm, additive
};

// VoronoiCellCount sites uniform in the opal (rejection from its bounding
// box), weights uniform in [0, VoronoiWeightSpread]; drawn from `random` in order.
std::vector<VoronoiSite> drawVoronoiSites(const ModelParameters& parameters, RandomSequence& random);

// Weighted distance |x - s| - w.
double weightedDistance(const VoronoiSite& site, const std::array<double, 3>& x);

// The weighted-nearest site by testing every site (ties: the lower index). For tests.
int nearestSiteBruteForce(const std::vector<VoronoiSite>& sites, const std::array<double, 3>& x);

class VoronoiSiteSearch
{
public:
  // Buckets the sites over the box [lo, hi] (mm) holding them.
  VoronoiSiteSearch(const std::vector<VoronoiSite>& sites, const std::array<double, 3>& lo,
    const std::array<double, 3>& hi);

  // The weighted-nearest site to x, a point of the box (ties: the lower
  // index), as nearestSiteBruteForce.
  int nearest(const std::array<double, 3>& x) const;

private:
  std::array<int, 3> bucketOf(const std::array<double, 3>& x) const;
  void bucketSites();
  // Calls visit(site) for the sites in the buckets at Chebyshev distance `ring` from bucket c.
  template <typename Visit>
  void forEachSiteInRing(const std::array<int, 3>& c, int ring, Visit&& visit) const;
  // The sites that can be nearest to some point of bucket c, in increasing index.
  std::vector<int> candidatesOf(const std::array<int, 3>& c) const;

  const std::vector<VoronoiSite>& Sites;
  std::array<double, 3> Lo{};
  double BucketSize = 1;
  std::array<int, 3> Buckets{};
  double MaxWeight = 0;
  std::vector<int> BucketStart; // sites of bucket b: BucketSites[BucketStart[b], BucketStart[b + 1])
  std::vector<int> BucketSites;
  std::vector<int> CandidateStart; // candidates of bucket b: Candidates[CandidateStart[b], CandidateStart[b + 1])
  std::vector<int> Candidates;
};

// The cell of every voxel of the grid (x fastest), -1 outside the opal.
// progress(fraction) may return false to abort: then the result is empty.
std::vector<std::int32_t> assignVoronoiCells(const Grid& grid, const HalfEllipsoid& shape,
  const VoronoiSiteSearch& search, const std::function<bool(double)>& progress = nullptr);

// Each cell's neighbours (sorted): two cells are adjacent where a voxel of
// each shares a face.
std::vector<std::vector<int>> voronoiAdjacency(const Grid& grid, const std::vector<std::int32_t>& cells, int cellCount);

} // namespace opal
