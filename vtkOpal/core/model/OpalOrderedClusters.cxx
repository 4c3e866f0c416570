#include "OpalOrderedClusters.h"

#include <algorithm>
#include <cmath>

namespace opal
{

std::vector<std::uint8_t> orderedCells(const std::vector<std::vector<int>>& neighbours,
  const std::vector<std::uint8_t>& hasVoxels, double fraction, RandomSequence& random)
{
  const std::size_t cellCount = neighbours.size();
  std::vector<double> value(cellCount);
  for (double& v : value)
  {
    v = random.uniform();
  }
  std::vector<std::pair<double, int>> ranked; // (-score, cell): ascending is best first
  for (std::size_t c = 0; c < cellCount; ++c)
  {
    if (!hasVoxels[c])
    {
      continue;
    }
    double sum = value[c];
    for (int n : neighbours[c])
    {
      sum += value[static_cast<std::size_t>(n)];
    }
    ranked.emplace_back(-sum / static_cast<double>(neighbours[c].size() + 1), static_cast<int>(c));
  }
  const auto target = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(ranked.size())));
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(target), ranked.end());
  std::vector<std::uint8_t> ordered(cellCount, 0);
  for (std::size_t r = 0; r < target; ++r)
  {
    ordered[static_cast<std::size_t>(ranked[r].second)] = 1;
  }
  return ordered;
}

} // namespace opal
