#include "vtkOpalRankWait.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>

namespace vtkOpalRankWait
{
namespace
{
using Clock = std::chrono::steady_clock;

// The wait in force (one at a time: a rank's collectives are called in turn),
// watched by one thread of the process.
struct Watch
{
  std::mutex Mutex;
  std::condition_variable Changed;
  std::uint64_t Serial = 0; // the wait in force; 0: none
  std::uint64_t LastSerial = 0;
  Clock::time_point Deadline;
  std::string Sentence; // said where the deadline passes within the wait
};

// The watching thread: where a wait is still in force at its deadline, it says
// so and ends the process (MPI offers no way out of the collective).
void watchWaits(Watch& watch)
{
  std::unique_lock<std::mutex> lock(watch.Mutex);
  for (;;)
  {
    watch.Changed.wait(lock, [&] { return watch.Serial != 0; });
    const std::uint64_t serial = watch.Serial;
    if (!watch.Changed.wait_until(lock, watch.Deadline, [&] { return watch.Serial != serial; }))
    {
      std::fputs(watch.Sentence.c_str(), stderr);
      std::fflush(stderr);
      std::_Exit(WaitExitCode);
    }
  }
}

Watch& theWatch()
{
  // Never destroyed: its thread waits on it until the process ends.
  static Watch* const watch = [] {
    auto* made = new Watch;
    std::thread(watchWaits, std::ref(*made)).detach();
    return made;
  }();
  return *watch;
}

thread_local std::string named = "an exchange between the ranks";

std::string secondsText(double seconds)
{
  std::ostringstream text;
  text << seconds;
  return text.str();
}

std::string sentence(vtkMultiProcessController* controller, double limit)
{
  const std::string waited = secondsText(limit) + " s";
  return "Rank " + std::to_string(controller->GetLocalProcessId()) + " of " +
    std::to_string(controller->GetNumberOfProcesses()) + " waited " + waited + " in " + named +
    " for the other ranks, the limit " + LimitVariable + " sets: a rank never came to it (its pipeline " +
    "failed or stopped before it, or its device hangs). This rank ends its process, and so the MPI job; " +
    "where a rank's work between two exchanges takes longer, set " + LimitVariable +
    " to more seconds (0: no bound).\n";
}
} // namespace

double LimitSeconds()
{
  const char* text = std::getenv(LimitVariable);
  if (!text || !*text)
  {
    return DefaultLimitSeconds;
  }
  // from_chars, not strtod: the same reading whatever the locale's decimal point.
  double seconds = 0;
  const char* end = text + std::char_traits<char>::length(text);
  const std::from_chars_result read = std::from_chars(text, end, seconds);
  if (read.ec == std::errc() && read.ptr == end && std::isfinite(seconds) && seconds >= 0)
  {
    return seconds;
  }
  static std::atomic<bool> said{ false };
  if (!said.exchange(true))
  {
    std::fprintf(stderr, "%s=%s is not a number of seconds at least 0 (0: no bound): the default %s s holds.\n",
      LimitVariable, text, secondsText(DefaultLimitSeconds).c_str());
  }
  return DefaultLimitSeconds;
}

Naming::Naming(std::string exchange)
  : Outer(std::move(named))
{
  named = std::move(exchange);
}

Naming::~Naming()
{
  named = std::move(this->Outer);
}

Bounded::Bounded(vtkMultiProcessController* controller)
{
  const double limit = LimitSeconds();
  if (limit <= 0)
  {
    return;
  }
  Watch& watch = theWatch();
  // At most ~30 years: a longer duration would overflow the clock's.
  const auto length = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(limit, 1e9)));
  std::string said = sentence(controller, limit);
  {
    const std::lock_guard<std::mutex> lock(watch.Mutex);
    this->Serial = ++watch.LastSerial;
    watch.Serial = this->Serial;
    watch.Deadline = Clock::now() + length;
    watch.Sentence = std::move(said);
  }
  watch.Changed.notify_one();
}

Bounded::~Bounded()
{
  if (this->Serial == 0)
  {
    return;
  }
  Watch& watch = theWatch();
  {
    const std::lock_guard<std::mutex> lock(watch.Mutex);
    if (watch.Serial == this->Serial)
    {
      watch.Serial = 0;
    }
  }
  watch.Changed.notify_one();
}
} // namespace vtkOpalRankWait
