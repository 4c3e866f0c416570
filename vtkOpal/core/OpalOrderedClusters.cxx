#include "OpalOrderedClusters.h"

#include <cmath>
#include <deque>
#include <utility>

namespace opal
{

namespace
{
// The cells with voxels in a random order (Fisher-Yates): the seeds' order.
std::vector<int> shuffledCells(const std::vector<std::uint8_t>& hasVoxels, RandomSequence& random)
{
  std::vector<int> cells;
  for (std::size_t c = 0; c < hasVoxels.size(); ++c)
  {
    if (hasVoxels[c])
    {
      cells.push_back(static_cast<int>(c));
    }
  }
  for (std::size_t i = cells.size(); i > 1; --i)
  {
    const auto j = static_cast<std::size_t>(random.uniformInt(0, static_cast<int>(i) - 1));
    std::swap(cells[i - 1], cells[j]);
  }
  return cells;
}
} // namespace

std::vector<std::uint8_t> growOrderedClusters(const std::vector<std::vector<int>>& neighbours,
  const std::vector<std::uint8_t>& hasVoxels, double fraction, RandomSequence& random)
{
  std::vector<std::uint8_t> ordered(neighbours.size(), 0);
  const std::vector<int> seeds = shuffledCells(hasVoxels, random);
  const auto target = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(seeds.size())));
  // The cluster in which a cell was tested and refused: refused once per cluster.
  std::vector<int> refusedIn(neighbours.size(), -1);
  std::size_t count = 0;
  int cluster = 0;
  for (auto seedIt = seeds.begin(); seedIt != seeds.end() && count < target; ++seedIt)
  {
    if (ordered[static_cast<std::size_t>(*seedIt)])
    {
      continue;
    }
    ++cluster;
    ordered[static_cast<std::size_t>(*seedIt)] = 1;
    ++count;
    std::deque<int> frontier{ *seedIt };
    while (!frontier.empty() && count < target)
    {
      const int cell = frontier.front();
      frontier.pop_front();
      for (int next : neighbours[static_cast<std::size_t>(cell)])
      {
        const auto n = static_cast<std::size_t>(next);
        if (count >= target || ordered[n] || refusedIn[n] == cluster || !hasVoxels[n])
        {
          continue;
        }
        if (random.uniform() < fraction)
        {
          ordered[n] = 1;
          ++count;
          frontier.push_back(next);
        }
        else
        {
          refusedIn[n] = cluster;
        }
      }
    }
  }
  return ordered;
}

} // namespace opal
