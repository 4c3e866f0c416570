// One parallel loop for the model's work (docs/design.md §2.7): a range of
// indices split into contiguous chunks over std::threads. Every value the
// model computes derives from global indices, so the split never changes a
// result.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace opal
{

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
    const int from = begin + static_cast<int>(static_cast<long long>(count) * t / threads);
    const int to = begin + static_cast<int>(static_cast<long long>(count) * (t + 1) / threads);
    workers.emplace_back([&functor, from, to] { functor(from, to); });
  }
  for (std::thread& worker : workers)
  {
    worker.join();
  }
}

} // namespace opal
