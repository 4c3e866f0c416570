#include "OpalVoronoiCells.h"

#include "OpalParallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

namespace opal
{

std::vector<VoronoiSite> drawVoronoiSites(const ModelParameters& p, RandomSequence& random)
{
  const HalfEllipsoid shape(p.SemiAxes);
  std::vector<VoronoiSite> sites;
  sites.reserve(static_cast<std::size_t>(p.VoronoiCellCount));
  while (static_cast<int>(sites.size()) < p.VoronoiCellCount)
  {
    // The half-ellipsoid fills pi/3 of its box: about 2 draws per site.
    const std::array<double, 3> x{ random.uniform(-p.SemiAxes[0], p.SemiAxes[0]), random.uniform(0.0, p.SemiAxes[1]),
      random.uniform(-p.SemiAxes[2], p.SemiAxes[2]) };
    if (shape.contains(x))
    {
      sites.push_back({ x, random.uniform(0.0, p.VoronoiWeightSpread) });
    }
  }
  return sites;
}

double weightedDistance(const VoronoiSite& site, const std::array<double, 3>& x)
{
  const double dx = x[0] - site.Position[0], dy = x[1] - site.Position[1], dz = x[2] - site.Position[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz) - site.Weight;
}

int nearestSiteBruteForce(const std::vector<VoronoiSite>& sites, const std::array<double, 3>& x)
{
  int best = -1;
  double bestDistance = 0;
  for (std::size_t i = 0; i < sites.size(); ++i)
  {
    const double d = weightedDistance(sites[i], x);
    if (best < 0 || d < bestDistance)
    {
      best = static_cast<int>(i);
      bestDistance = d;
    }
  }
  return best;
}

VoronoiSiteSearch::VoronoiSiteSearch(
  const std::vector<VoronoiSite>& sites, const std::array<double, 3>& lo, const std::array<double, 3>& hi)
  : Sites(sites)
  , Lo(lo)
{
  // About one site per bucket, at most 1024 buckets, and no more than sites,
  // along an axis (the bucket cube must cover the box for the search's
  // distance bounds). Without the second bound a thin, long box (semi-axes
  // 0.01, 0.01, 10 mm) of 60 sites took 500 buckets along it, and each
  // bucket's search walked rings across all of them: a minute under the
  // fuzzer's sanitizers for one layout.
  const std::array<double, 3> size{ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] };
  const double volume = size[0] * size[1] * size[2];
  const double siteCount = static_cast<double>(std::max<std::size_t>(1, sites.size()));
  const double widest = std::max({ size[0], size[1], size[2] });
  this->BucketSize =
    std::max({ std::cbrt(volume / siteCount), widest / 1024, widest / siteCount, 1e-12 });
  for (int a = 0; a < 3; ++a)
  {
    const double cells = std::ceil(size[a] / this->BucketSize);
    this->Buckets[a] = static_cast<int>(std::clamp(cells, 1.0, 1024.0));
  }
  this->bucketSites();
  const int bucketCount = this->Buckets[0] * this->Buckets[1] * this->Buckets[2];
  std::vector<std::vector<int>> candidates(static_cast<std::size_t>(bucketCount));
  parallelFor(0, bucketCount, [&](int begin, int end) {
    for (int b = begin; b < end; ++b)
    {
      const std::array<int, 3> c{ b % this->Buckets[0], (b / this->Buckets[0]) % this->Buckets[1],
        b / (this->Buckets[0] * this->Buckets[1]) };
      candidates[static_cast<std::size_t>(b)] = this->candidatesOf(c);
    }
  });
  this->CandidateStart.assign(1, 0);
  for (const std::vector<int>& list : candidates)
  {
    this->Candidates.insert(this->Candidates.end(), list.begin(), list.end());
    this->CandidateStart.push_back(static_cast<int>(this->Candidates.size()));
  }
}

// Counting sort of the sites into their buckets, each bucket's in increasing index.
void VoronoiSiteSearch::bucketSites()
{
  const std::size_t bucketCount = static_cast<std::size_t>(this->Buckets[0]) * this->Buckets[1] * this->Buckets[2];
  std::vector<int> bucketOfSite(this->Sites.size());
  this->BucketStart.assign(bucketCount + 1, 0);
  for (std::size_t i = 0; i < this->Sites.size(); ++i)
  {
    const std::array<int, 3> b = this->bucketOf(this->Sites[i].Position);
    bucketOfSite[i] = b[0] + this->Buckets[0] * (b[1] + this->Buckets[1] * b[2]);
    ++this->BucketStart[static_cast<std::size_t>(bucketOfSite[i]) + 1];
    this->MaxWeight = std::max(this->MaxWeight, this->Sites[i].Weight);
  }
  for (std::size_t b = 0; b < bucketCount; ++b)
  {
    this->BucketStart[b + 1] += this->BucketStart[b];
  }
  std::vector<int> fill(this->BucketStart.begin(), this->BucketStart.end() - 1);
  this->BucketSites.resize(this->Sites.size());
  for (std::size_t i = 0; i < this->Sites.size(); ++i)
  {
    this->BucketSites[static_cast<std::size_t>(fill[static_cast<std::size_t>(bucketOfSite[i])]++)] = static_cast<int>(i);
  }
}

std::array<int, 3> VoronoiSiteSearch::bucketOf(const std::array<double, 3>& x) const
{
  std::array<int, 3> b{};
  for (int a = 0; a < 3; ++a)
  {
    const double cell = std::floor((x[a] - this->Lo[a]) / this->BucketSize);
    b[a] = static_cast<int>(std::clamp(cell, 0.0, static_cast<double>(this->Buckets[a] - 1)));
  }
  return b;
}

template <typename Visit>
void VoronoiSiteSearch::forEachSiteInRing(const std::array<int, 3>& c, int ring, Visit&& visit) const
{
  for (int bz = std::max(0, c[2] - ring); bz <= std::min(this->Buckets[2] - 1, c[2] + ring); ++bz)
  {
    for (int by = std::max(0, c[1] - ring); by <= std::min(this->Buckets[1] - 1, c[1] + ring); ++by)
    {
      // Inside the shell's y-z cross-section only the two x ends belong to the ring.
      const bool shell = std::abs(bz - c[2]) == ring || std::abs(by - c[1]) == ring;
      const int step = shell || ring == 0 ? 1 : 2 * ring;
      for (int bx = c[0] - ring; bx <= c[0] + ring; bx += step)
      {
        if (bx < 0 || bx >= this->Buckets[0])
        {
          continue;
        }
        const std::size_t b = static_cast<std::size_t>(bx + this->Buckets[0] * (by + this->Buckets[1] * bz));
        for (int s = this->BucketStart[b]; s < this->BucketStart[b + 1]; ++s)
        {
          visit(this->BucketSites[static_cast<std::size_t>(s)]);
        }
      }
    }
  }
}

// A site can be nearest somewhere in the bucket only if its smallest weighted
// distance to the bucket's box is at most the smallest largest one of any
// site. Sites in ring r lie at least (r - 1) bucket sizes away, so the rings
// are visited outward until that bound, less the largest weight, passes the
// smallest largest distance found.
std::vector<int> VoronoiSiteSearch::candidatesOf(const std::array<int, 3>& c) const
{
  std::array<double, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = this->Lo[a] + c[a] * this->BucketSize;
    hi[a] = lo[a] + this->BucketSize;
  }
  std::vector<std::pair<int, double>> near; // (site, smallest weighted distance to the box)
  double bestLargest = std::numeric_limits<double>::infinity();
  const int maxRing = std::max({ this->Buckets[0], this->Buckets[1], this->Buckets[2] });
  for (int ring = 0; ring <= maxRing && (ring - 1) * this->BucketSize - this->MaxWeight <= bestLargest; ++ring)
  {
    this->forEachSiteInRing(c, ring, [&](int site) {
      const VoronoiSite& s = this->Sites[static_cast<std::size_t>(site)];
      double smallest = 0, largest = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double gap = std::max({ lo[a] - s.Position[a], 0.0, s.Position[a] - hi[a] });
        const double reach = std::max(std::fabs(s.Position[a] - lo[a]), std::fabs(s.Position[a] - hi[a]));
        smallest += gap * gap;
        largest += reach * reach;
      }
      near.emplace_back(site, std::sqrt(smallest) - s.Weight);
      bestLargest = std::min(bestLargest, std::sqrt(largest) - s.Weight);
    });
  }
  std::vector<int> candidates;
  for (const auto& [site, smallest] : near)
  {
    if (smallest <= bestLargest)
    {
      candidates.push_back(site);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  return candidates;
}

int VoronoiSiteSearch::nearest(const std::array<double, 3>& x) const
{
  const std::array<int, 3> c = this->bucketOf(x);
  const std::size_t b = static_cast<std::size_t>(c[0] + this->Buckets[0] * (c[1] + this->Buckets[1] * c[2]));
  int best = -1;
  double bestDistance = 0;
  for (int i = this->CandidateStart[b]; i < this->CandidateStart[b + 1]; ++i)
  {
    const int site = this->Candidates[static_cast<std::size_t>(i)];
    const double d = weightedDistance(this->Sites[static_cast<std::size_t>(site)], x);
    if (best < 0 || d < bestDistance)
    {
      best = site;
      bestDistance = d;
    }
  }
  return best;
}

VoronoiCellRuns::VoronoiCellRuns(
  const std::array<int, 3>& dimensions, std::vector<std::int64_t> rowStart, std::vector<Run> runs)
  : Dimensions(dimensions)
  , RowStart(std::move(rowStart))
  , Runs(std::move(runs))
{
}

const VoronoiCellRuns::Run* VoronoiCellRuns::runAt(int i, int j, int k) const
{
  const Run* end = this->rowEnd(j, k);
  // The last run starting at or before i (the first starts at 0).
  return std::upper_bound(this->rowBegin(j, k), end, i, [](int x, const Run& run) { return x < run.FirstX; }) - 1;
}

namespace
{
// A row's cells as runs, appended to `runs`.
void appendRuns(const std::vector<std::int32_t>& line, std::vector<VoronoiCellRuns::Run>& runs)
{
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    if (i == 0 || line[i] != line[i - 1])
    {
      runs.push_back({ static_cast<std::int32_t>(i), line[i] });
    }
  }
}
} // namespace

VoronoiCellRuns assignVoronoiCells(const Grid& grid, const HalfEllipsoid& shape, const VoronoiSiteSearch& search,
  const std::array<int, 2>& zRange, const std::function<bool(double)>& progress)
{
  const int nx = grid.Dimensions[0], ny = grid.Dimensions[1], nz = zRange[1] - zRange[0];
  std::vector<std::int64_t> rowStart(1, 0);
  rowStart.reserve(static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz) + 1);
  std::vector<VoronoiCellRuns::Run> runs;
  const int chunk = std::max(1, nz / 20);
  for (int k0 = zRange[0]; k0 < zRange[1]; k0 += chunk)
  {
    const int k1 = std::min(zRange[1], k0 + chunk);
    // Each layer's rows encoded apart, then appended in order.
    std::vector<std::vector<VoronoiCellRuns::Run>> layers(static_cast<std::size_t>(k1 - k0));
    std::vector<std::vector<std::int64_t>> layerRowEnds(layers.size());
    parallelFor(k0, k1, [&](int begin, int end) {
      std::vector<std::int32_t> line(static_cast<std::size_t>(nx));
      for (int k = begin; k < end; ++k)
      {
        const std::size_t layer = static_cast<std::size_t>(k - k0);
        for (int j = 0; j < ny; ++j)
        {
          for (int i = 0; i < nx; ++i)
          {
            const std::array<double, 3> x = grid.position(i, j, k);
            line[static_cast<std::size_t>(i)] = shape.contains(x) ? search.nearest(x) : -1;
          }
          appendRuns(line, layers[layer]);
          layerRowEnds[layer].push_back(static_cast<std::int64_t>(layers[layer].size()));
        }
      }
    });
    for (std::size_t layer = 0; layer < layers.size(); ++layer)
    {
      const std::int64_t offset = static_cast<std::int64_t>(runs.size());
      runs.insert(runs.end(), layers[layer].begin(), layers[layer].end());
      for (std::int64_t rowEnd : layerRowEnds[layer])
      {
        rowStart.push_back(offset + rowEnd);
      }
    }
    if (progress && !progress(static_cast<double>(k1 - zRange[0]) / nz))
    {
      return {};
    }
  }
  runs.shrink_to_fit();
  return VoronoiCellRuns({ nx, ny, nz }, std::move(rowStart), std::move(runs));
}

namespace
{
// `count` values of T read from `bytes` at `at`, which moves past them.
template <typename T>
std::vector<T> readBytes(const std::vector<char>& bytes, std::size_t& at, std::size_t count)
{
  if (count > (bytes.size() - at) / sizeof(T))
  {
    throw std::runtime_error("Voronoi cell runs: the bytes end early.");
  }
  std::vector<T> values(count);
  if (count > 0)
  {
    std::memcpy(values.data(), bytes.data() + at, count * sizeof(T));
  }
  at += count * sizeof(T);
  return values;
}
} // namespace

std::vector<char> VoronoiCellRuns::bytes() const
{
  const std::int64_t dims[3] = { this->Dimensions[0], this->Dimensions[1], this->Dimensions[2] };
  const std::size_t starts = this->RowStart.size() * sizeof(std::int64_t);
  const std::size_t runs = this->Runs.size() * sizeof(Run);
  std::vector<char> bytes(sizeof(dims) + starts + runs);
  std::memcpy(bytes.data(), dims, sizeof(dims));
  if (starts > 0) // an empty vector's data() may be null, which memcpy may not take
  {
    std::memcpy(bytes.data() + sizeof(dims), this->RowStart.data(), starts);
  }
  if (runs > 0)
  {
    std::memcpy(bytes.data() + sizeof(dims) + starts, this->Runs.data(), runs);
  }
  return bytes;
}

VoronoiCellRuns VoronoiCellRuns::fromBytes(const std::vector<char>& bytes)
{
  std::size_t at = 0;
  const std::vector<std::int64_t> dims = readBytes<std::int64_t>(bytes, at, 3);
  if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0 || d > (std::int64_t(1) << 30); }))
  {
    throw std::runtime_error("Voronoi cell runs: the bytes name no grid.");
  }
  std::vector<std::int64_t> rowStart = readBytes<std::int64_t>(bytes, at, static_cast<std::size_t>(dims[1] * dims[2] + 1));
  const std::size_t runCount = (bytes.size() - at) / sizeof(Run);
  std::vector<Run> runs = readBytes<Run>(bytes, at, runCount);
  const bool ordered = rowStart.front() == 0 && std::is_sorted(rowStart.begin(), rowStart.end());
  if (at != bytes.size() || !ordered || rowStart.back() != static_cast<std::int64_t>(runs.size()))
  {
    throw std::runtime_error("Voronoi cell runs: the bytes' rows do not hold their runs.");
  }
  return VoronoiCellRuns({ static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2]) },
    std::move(rowStart), std::move(runs));
}

bool VoronoiCellRuns::wellFormed(int cellCount) const
{
  for (std::size_t row = 0; row + 1 < this->RowStart.size(); ++row)
  {
    const Run* begin = this->Runs.data() + this->RowStart[row];
    const Run* end = this->Runs.data() + this->RowStart[row + 1];
    if (begin == end || begin->FirstX != 0)
    {
      return false;
    }
    for (const Run* run = begin; run != end; ++run)
    {
      const bool ordered = run == begin || (run[-1].FirstX < run->FirstX && run->FirstX < this->Dimensions[0]);
      if (!ordered || run->Cell < -1 || run->Cell >= cellCount)
      {
        return false;
      }
    }
  }
  return true;
}

VoronoiCellRuns VoronoiCellRuns::stacked(const std::vector<VoronoiCellRuns>& layers)
{
  std::array<int, 3> dims{ layers.empty() ? 0 : layers.front().Dimensions[0],
    layers.empty() ? 0 : layers.front().Dimensions[1], 0 };
  std::vector<std::int64_t> rowStart(1, 0);
  std::vector<Run> runs;
  for (const VoronoiCellRuns& part : layers)
  {
    if (part.Dimensions[0] != dims[0] || part.Dimensions[1] != dims[1])
    {
      throw std::runtime_error("Voronoi cell runs: stacked layers of unlike rows.");
    }
    const std::int64_t offset = static_cast<std::int64_t>(runs.size());
    for (std::size_t r = 1; r < part.RowStart.size(); ++r)
    {
      rowStart.push_back(offset + part.RowStart[r]);
    }
    runs.insert(runs.end(), part.Runs.begin(), part.Runs.end());
    dims[2] += part.Dimensions[2];
  }
  return VoronoiCellRuns(dims, std::move(rowStart), std::move(runs));
}

std::uint64_t voronoiCellRunBytes(const std::array<int, 3>& dimensions, int cellCount)
{
  const double voxels = static_cast<double>(dimensions[0]) * dimensions[1] * dimensions[2];
  const double cellsAcross = std::min(1.0, std::cbrt(std::max(cellCount, 1) / voxels)) * dimensions[0];
  const double rows = static_cast<double>(dimensions[1]) * dimensions[2];
  return static_cast<std::uint64_t>(rows * ((cellsAcross + 2) * sizeof(VoronoiCellRuns::Run) + sizeof(std::int64_t)));
}

namespace
{
// Calls link(a, b) for the cells of every pair of overlapping runs of two rows.
template <typename Link>
void linkOverlappingRuns(const VoronoiCellRuns& cells, int j0, int k0, int j1, int k1, Link&& link)
{
  const VoronoiCellRuns::Run *a = cells.rowBegin(j0, k0), *aEnd = cells.rowEnd(j0, k0);
  const VoronoiCellRuns::Run *b = cells.rowBegin(j1, k1), *bEnd = cells.rowEnd(j1, k1);
  while (a != aEnd && b != bEnd)
  {
    link(a->Cell, b->Cell);
    const int aStop = cells.runEnd(a, aEnd), bStop = cells.runEnd(b, bEnd);
    a += aStop <= bStop ? 1 : 0;
    b += bStop <= aStop ? 1 : 0;
  }
}
} // namespace

std::vector<std::vector<int>> voronoiAdjacency(const VoronoiCellRuns& cells, int cellCount)
{
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(cellCount));
  const auto link = [&neighbours](std::int32_t here, std::int32_t there) {
    if (here >= 0 && there >= 0 && here != there)
    {
      neighbours[static_cast<std::size_t>(here)].push_back(there);
      neighbours[static_cast<std::size_t>(there)].push_back(here);
    }
  };
  const std::array<int, 3>& dims = cells.dimensions();
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      const VoronoiCellRuns::Run* begin = cells.rowBegin(j, k);
      for (const VoronoiCellRuns::Run* run = begin + 1; run < cells.rowEnd(j, k); ++run)
      {
        link(run[-1].Cell, run->Cell);
      }
      if (j + 1 < dims[1])
      {
        linkOverlappingRuns(cells, j, k, j + 1, k, link);
      }
      if (k + 1 < dims[2])
      {
        linkOverlappingRuns(cells, j, k, j, k + 1, link);
      }
    }
  }
  for (std::vector<int>& list : neighbours)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

} // namespace opal
