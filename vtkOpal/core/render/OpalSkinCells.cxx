#include "OpalSkinCells.h"

#include "OpalParallel.h"

#include <algorithm>
#include <cmath>

namespace opal
{

namespace
{
// The inside neighbour of cell (i, j, k) with the smallest SurfaceDistance, or -1.
std::int64_t deepestInsideNeighbour(const RenderVolume& volume, int i, int j, int k)
{
  const auto& n = volume.Dimensions;
  std::int64_t best = -1;
  float deepest = 0.0f;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
      {
        const int a = i + di, b = j + dj, c = k + dk;
        if (a < 0 || b < 0 || c < 0 || a >= n[0] || b >= n[1] || c >= n[2])
          continue;
        const std::int64_t index = a + static_cast<std::int64_t>(n[0]) * (b + static_cast<std::int64_t>(n[1]) * c);
        const float d = volume.SurfaceDistance[index];
        if (d <= 0.0f && (best < 0 || d < deepest))
        {
          best = index;
          deepest = d;
        }
      }
  return best;
}
} // namespace

std::vector<SkinCell> skinCells(const RenderVolume& volume, std::pair<int, int> layers)
{
  const auto& s = volume.Spacing;
  const auto diagonal = static_cast<float>(std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
  const auto& n = volume.Dimensions;
  const auto first = static_cast<std::int64_t>(volume.mediumFirstVoxel());
  std::vector<std::vector<SkinCell>> perSlice(static_cast<std::size_t>(std::max(layers.second - layers.first, 0)));
  parallelFor(layers.first, layers.second, [&](int kBegin, int kEnd) {
    for (int k = kBegin; k < kEnd; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          const std::int64_t index = i + static_cast<std::int64_t>(n[0]) * (j + static_cast<std::int64_t>(n[1]) * k);
          const float d = volume.SurfaceDistance[index];
          if (d <= 0.0f || d > diagonal || volume.ScatteringCoefficient[index - first] != 0.0f ||
            volume.DomainId[index - first] >= 0)
            continue;
          const std::int64_t source = deepestInsideNeighbour(volume, i, j, k);
          if (source >= 0)
            perSlice[static_cast<std::size_t>(k - layers.first)].push_back({ index, source });
        }
  });
  std::vector<SkinCell> cells;
  for (const auto& slice : perSlice)
  {
    cells.insert(cells.end(), slice.begin(), slice.end());
  }
  return cells;
}

} // namespace opal
