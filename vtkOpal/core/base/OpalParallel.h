// One parallel loop for the model's work (docs/design.md §2.7): a range of
// indices split into contiguous chunks over std::threads. Every value the
// model computes derives from global indices, so the split never changes a
// result.
#pragma once

#include <algorithm>
#include <cstdint>
#include <thread>
#include <utility>
#include <vector>

namespace opal
{

// Share `share` of `shares` of [0, count): [floor(count s / N), floor(count
// (s + 1) / N)). The shares are contiguous, in order, and differ by one at
// most: parallelFor's chunks, and the ranks' shares of the light field's rows
// and of the Voronoi layers (docs/design.md §8.1).
inline std::pair<int, int> evenShare(int count, int share, int shares)
{
  const auto at = [&](int s) { return static_cast<int>(static_cast<std::int64_t>(count) * s / shares); };
  return { at(share), at(share + 1) };
}

// The largest share of evenShare's: ceil(count / shares).
inline int mostInShare(int count, int shares)
{
  return static_cast<int>((static_cast<std::int64_t>(count) + shares - 1) / shares);
}

// Calls functor(begin, end) on disjoint chunks covering [begin, end), one per
// hardware thread, and returns when all are done.
template <typename Functor>
void parallelFor(int begin, int end, Functor&& functor)
{
  const int count = end - begin;
  const int threads = std::max(1, std::min<int>(count, static_cast<int>(std::thread::hardware_concurrency())));
  if (threads <= 1)
  {
    if (count > 0)
    {
      functor(begin, end);
    }
    return;
  }
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t)
  {
    const std::pair<int, int> chunk = evenShare(count, t, threads);
    workers.emplace_back([&functor, from = begin + chunk.first, to = begin + chunk.second] { functor(from, to); });
  }
  for (std::thread& worker : workers)
  {
    worker.join();
  }
}

} // namespace opal
