// How much work one submit takes (docs/design.md §3.7): about TargetSeconds
// of it, from the measured cost of the last submit of the same pass, so that
// no submit runs long enough to trip a display GPU's watchdog (a few
// seconds) on any device, and a fast device is not held to a slow one's
// counts. Each submit costs a wait for the device; a quarter second keeps
// that cost small and abort and progress prompt.
#pragma once

#include <algorithm>
#include <cstdint>

namespace opal
{

class SubmitPacer
{
public:
  static constexpr double TargetSeconds = 0.25;

  // `initialItems` per submit until one was measured.
  explicit SubmitPacer(std::int64_t initialItems)
    : SecondsPerItem(TargetSeconds / static_cast<double>(std::max<std::int64_t>(initialItems, 1)))
  {
  }

  // The items the next submit should take, at least one.
  std::int64_t items() const
  {
    return std::max<std::int64_t>(1, static_cast<std::int64_t>(TargetSeconds / this->SecondsPerItem));
  }

  // A submit of `items` took `seconds`.
  void measured(std::int64_t items, double seconds)
  {
    if (items > 0 && seconds > 0)
    {
      this->SecondsPerItem = seconds / static_cast<double>(items);
    }
  }

private:
  double SecondsPerItem;
};

} // namespace opal
