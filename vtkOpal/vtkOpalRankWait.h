// A bound on each wait of a rank in an exchange with the others
// (docs/design.md §8.2). MPI has no way out of a collective that another
// rank never enters (its pipeline failed before the render, it stopped, its
// device hangs): the others would wait forever. A rank still waiting in one
// after the limit says so on its standard error, naming the exchange and the
// limit, and ends its process with WaitExitCode, which ends the MPI job
// where the launcher ends a job for a rank's failure (mpiexec does; Slurm's
// srun with --kill-on-bad-exit).
#pragma once

#include <cstdint>
#include <string>

class vtkMultiProcessController;

namespace vtkOpalRankWait
{
// The environment variable that sets the limit, in seconds (0: no bound); read
// at each exchange, so a script may set it at any time before one.
constexpr const char* LimitVariable = "OPAL_EXCHANGE_WAIT_LIMIT";
// A rank's work between two exchanges can take minutes at 10 µm (a slab of the
// light pass, a round of the march): the default is well beyond, so that it
// ends only a job that waits for a rank that will not come.
constexpr double DefaultLimitSeconds = 1800;
// The process's exit status where a wait ran past the limit.
constexpr int WaitExitCode = 3;

// The limit in force, in seconds: the variable's value, the default where it
// is unset, and where it is not a number of seconds at least 0, the default
// (said once, naming the variable).
double LimitSeconds();

// While one lives, this thread's exchanges are `exchange` in the sentence
// ("the ranks' agreement before the render"); the innermost names them.
class Naming
{
public:
  explicit Naming(std::string exchange);
  ~Naming();
  Naming(const Naming&) = delete;
  Naming& operator=(const Naming&) = delete;

private:
  std::string Outer;
};

// Held across one collective call of `controller` (more than one process):
// bounds its wait by LimitSeconds(). One at a time, as a rank's collectives
// are: a second one held at once would take the bound off the first.
class Bounded
{
public:
  explicit Bounded(vtkMultiProcessController* controller);
  ~Bounded();
  Bounded(const Bounded&) = delete;
  Bounded& operator=(const Bounded&) = delete;

private:
  std::uint64_t Serial = 0; // 0: unbounded (no limit)
};
} // namespace vtkOpalRankWait
