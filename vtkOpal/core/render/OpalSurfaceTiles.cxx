#include "OpalSurfaceTiles.h"

#include "OpalParallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace opal
{
namespace
{
// A point of one axis where the trilinear read takes an extreme over a
// tile: (1 - w) of voxel First and w of voxel Second. Within the grid the
// read is multilinear over each cell, so its extremes over the cells lie at
// their corners, the voxels (w = 0); the outermost cells' reads continue
// half a cell beyond the outermost centres (trilinearSurfaceDistance clamps
// the point to the grid's box), whose ends are corners too (w = -0.5, 1.5).
struct AxisNode
{
  int First, Second;
  double W;
};

// The extreme points along one axis of `n` voxels for tile t of `cells` cells.
std::vector<AxisNode> axisNodes(int n, int cells, int t)
{
  std::vector<AxisNode> nodes;
  const int first = t * cells;
  for (int k = 0; k <= cells; ++k)
  {
    const int voxel = std::min(first + k, n - 1);
    nodes.push_back({ voxel, voxel, 0.0 });
  }
  if (n >= 2 && first == 0)
  {
    nodes.push_back({ 0, 1, -0.5 });
  }
  if (n >= 2 && first + cells >= n - 1)
  {
    nodes.push_back({ n - 2, n - 1, 1.5 });
  }
  return nodes;
}

// The read at the point (x, y, z) of the axes' nodes.
double nodeValue(const RenderVolume& v, const AxisNode& x, const AxisNode& y, const AxisNode& z)
{
  const auto& d = v.Dimensions;
  if (x.W == 0.0 && y.W == 0.0 && z.W == 0.0)
  {
    return v.SurfaceDistance[static_cast<std::size_t>(x.First) +
      static_cast<std::size_t>(d[0]) * (static_cast<std::size_t>(y.First) + static_cast<std::size_t>(d[1]) * z.First)];
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const bool hx = corner & 1, hy = corner & 2, hz = corner & 4;
    const double w = (hx ? x.W : 1.0 - x.W) * (hy ? y.W : 1.0 - y.W) * (hz ? z.W : 1.0 - z.W);
    if (w != 0.0)
    {
      const std::size_t i = static_cast<std::size_t>(hx ? x.Second : x.First) +
        static_cast<std::size_t>(d[0]) *
          (static_cast<std::size_t>(hy ? y.Second : y.First) + static_cast<std::size_t>(d[1]) * (hz ? z.Second : z.First));
      sum += w * v.SurfaceDistance[i];
    }
  }
  return sum;
}

// The bound of tile `tile` with its sign, or NaN where the tile must be
// held: the read comes within `near` of 0 or changes sign in it.
double tileBound(const RenderVolume& v, int cells, const std::array<int, 3>& tile, double near)
{
  const std::vector<AxisNode> xs = axisNodes(v.Dimensions[0], cells, tile[0]);
  const std::vector<AxisNode> ys = axisNodes(v.Dimensions[1], cells, tile[1]);
  const std::vector<AxisNode> zs = axisNodes(v.Dimensions[2], cells, tile[2]);
  double least = std::numeric_limits<double>::infinity();
  int sign = 0;
  for (const AxisNode& z : zs)
  {
    for (const AxisNode& y : ys)
    {
      for (const AxisNode& x : xs)
      {
        const double value = nodeValue(v, x, y, z);
        const int side = value > 0.0 ? 1 : -1; // the inside is <= 0, as the traces read it
        if (std::abs(value) < near || (sign != 0 && side != sign))
        {
          return std::numeric_limits<double>::quiet_NaN();
        }
        sign = side;
        least = std::min(least, std::abs(value));
      }
    }
  }
  return sign * least;
}

// `value` as a float no further from 0 than it is: a bound rounded outward
// would let a trace step past the surface.
float boundTowardZero(double value)
{
  float f = static_cast<float>(value);
  if (std::abs(static_cast<double>(f)) > std::abs(value))
  {
    f = std::nextafter(f, 0.0f);
  }
  return f;
}

// Appends tile `tile`'s voxels (clamped to the grid) to `values`.
void holdTile(const RenderVolume& v, int cells, const std::array<int, 3>& tile, std::vector<float>& values)
{
  const auto& d = v.Dimensions;
  for (int k = 0; k <= cells; ++k)
  {
    const std::size_t z = static_cast<std::size_t>(std::min(tile[2] * cells + k, d[2] - 1));
    for (int j = 0; j <= cells; ++j)
    {
      const std::size_t y = static_cast<std::size_t>(std::min(tile[1] * cells + j, d[1] - 1));
      for (int i = 0; i <= cells; ++i)
      {
        const std::size_t x = static_cast<std::size_t>(std::min(tile[0] * cells + i, d[0] - 1));
        values.push_back(v.SurfaceDistance[x + static_cast<std::size_t>(d[0]) * (y + static_cast<std::size_t>(d[1]) * z)]);
      }
    }
  }
}
} // namespace

std::size_t SurfaceTiles::heldTiles() const
{
  return static_cast<std::size_t>(std::count_if(this->Slot.begin(), this->Slot.end(), [](std::int32_t s) { return s >= 0; }));
}

std::size_t SurfaceTiles::bytes() const
{
  return (this->Slot.size() + this->Bound.size() + this->Values.size()) * sizeof(float);
}

std::array<int, 3> surfaceTileCount(const std::array<int, 3>& dimensions, int cells)
{
  std::array<int, 3> count{};
  for (int a = 0; a < 3; ++a)
  {
    count[a] = (std::max(dimensions[a] - 1, 1) + cells - 1) / cells;
  }
  return count;
}

SurfaceTiles surfaceTiles(const RenderVolume& volume, int cells)
{
  if (cells < 1 || !volume.SurfaceDistance)
  {
    throw std::invalid_argument("surfaceTiles: tiles of at least one cell, of a volume with SurfaceDistance.");
  }
  SurfaceTiles tiles;
  tiles.Cells = cells;
  tiles.Count = surfaceTileCount(volume.Dimensions, cells);
  const std::size_t tileValues = static_cast<std::size_t>(cells + 1) * (cells + 1) * (cells + 1);
  const double near = SurfaceTileNearSpacings * std::max({ volume.Spacing[0], volume.Spacing[1], volume.Spacing[2] });
  // The bounds in parallel over the tiles' layers (each tile's alone), then
  // the held tiles' values in tile order.
  const int rowTiles = tiles.Count[0] * tiles.Count[1];
  std::vector<double> bounds(static_cast<std::size_t>(rowTiles) * tiles.Count[2]);
  parallelFor(0, tiles.Count[2], [&](int from, int to) {
    for (int z = from; z < to; ++z)
      for (int y = 0; y < tiles.Count[1]; ++y)
        for (int x = 0; x < tiles.Count[0]; ++x)
        {
          bounds[static_cast<std::size_t>(x + tiles.Count[0] * y) + static_cast<std::size_t>(rowTiles) * z] =
            tileBound(volume, cells, { x, y, z }, near);
        }
  });
  for (std::size_t i = 0; i < bounds.size(); ++i)
  {
    const bool held = std::isnan(bounds[i]);
    tiles.Slot.push_back(held ? static_cast<std::int32_t>(tiles.Values.size() / tileValues) : -1);
    tiles.Bound.push_back(held ? 0.0f : boundTowardZero(bounds[i]));
    if (held)
    {
      const int t = static_cast<int>(i % static_cast<std::size_t>(rowTiles));
      holdTile(volume, cells, { t % tiles.Count[0], t / tiles.Count[0], static_cast<int>(i / rowTiles) }, tiles.Values);
    }
  }
  return tiles;
}

} // namespace opal
