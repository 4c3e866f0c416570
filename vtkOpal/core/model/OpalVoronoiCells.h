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

// The cell of every voxel of the grid (-1 outside the opal), run-length
// encoded along x: a row's run of one cell's voxels is one (first x, cell)
// pair. Cells tens of voxels across then take a fraction of a byte per voxel,
// where an id per voxel took 4 (docs/design.md §2.9).
class VoronoiCellRuns
{
public:
  struct Run
  {
    std::int32_t FirstX = 0;
    std::int32_t Cell = -1;
  };

  VoronoiCellRuns() = default;
  // rowStart[r], r = j + ny k: the first of row r's runs in `runs`, the last
  // entry their count; each row's runs start at x = 0, increase in x, and
  // two in a row never hold the same cell.
  VoronoiCellRuns(const std::array<int, 3>& dimensions, std::vector<std::int64_t> rowStart, std::vector<Run> runs);

  bool empty() const { return this->RowStart.empty(); }
  const std::array<int, 3>& dimensions() const { return this->Dimensions; }
  // Row (j, k)'s runs, [rowBegin, rowEnd).
  const Run* rowBegin(int j, int k) const { return this->Runs.data() + this->RowStart[this->rowOf(j, k)]; }
  const Run* rowEnd(int j, int k) const { return this->Runs.data() + this->RowStart[this->rowOf(j, k) + 1]; }
  // The run of row (j, k) that holds voxel i.
  const Run* runAt(int i, int j, int k) const;
  std::int32_t cellAt(int i, int j, int k) const { return this->runAt(i, j, k)->Cell; }
  // Where the run ends: the next run's first x, or the row's end.
  int runEnd(const Run* run, const Run* rowEnd) const { return run + 1 != rowEnd ? run[1].FirstX : this->Dimensions[0]; }
  std::size_t runCount() const { return this->Runs.size(); }

  // The runs as bytes (the dimensions, each row's start, the runs) and back:
  // how ranks that share the assignment hand their layers over (docs/design.md
  // §8.1). fromBytes throws where the bytes are not runs of that layout.
  std::vector<char> bytes() const;
  static VoronoiCellRuns fromBytes(const std::vector<char>& bytes);
  // Whether every row holds runs from x = 0, increasing within the row, of
  // cells in [-1, cellCount): what the layout may index with them (runs
  // from bytes are checked for their shape only).
  bool wellFormed(int cellCount) const;
  // Runs of consecutive layers along z stacked in order into one grid's
  // (each of the same rows); throws where they differ.
  static VoronoiCellRuns stacked(const std::vector<VoronoiCellRuns>& layers);

private:
  std::size_t rowOf(int j, int k) const
  {
    return static_cast<std::size_t>(j) + static_cast<std::size_t>(this->Dimensions[1]) * static_cast<std::size_t>(k);
  }

  std::array<int, 3> Dimensions{};
  std::vector<std::int64_t> RowStart;
  std::vector<Run> Runs;
};

// The cell of every voxel of the grid's layers z = zRange[0] to zRange[1]
// (exclusive), -1 outside the opal: runs of nx x ny x (zRange[1] - zRange[0]).
// progress(fraction of those layers) may return false to abort: then the
// result is empty.
VoronoiCellRuns assignVoronoiCells(const Grid& grid, const HalfEllipsoid& shape, const VoronoiSiteSearch& search,
  const std::array<int, 2>& zRange, const std::function<bool(double)>& progress = nullptr);

// About the bytes of a grid's runs for `cellCount` cells: a row crosses about
// its length over a cell's diameter of them (at least one voxel), plus the
// outside on either side.
std::uint64_t voronoiCellRunBytes(const std::array<int, 3>& dimensions, int cellCount);

// Each cell's neighbours (sorted): two cells are adjacent where a voxel of
// each shares a face: along x, consecutive runs of a row; along y and z,
// overlapping runs of neighbouring rows.
std::vector<std::vector<int>> voronoiAdjacency(const VoronoiCellRuns& cells, int cellCount);

} // namespace opal
