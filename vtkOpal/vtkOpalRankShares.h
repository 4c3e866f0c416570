// A step that the ranks of an MPI render share before their frames
// (docs/design.md §8.1): every rank says whether it needs the step's result,
// those that do each compute a share and all exchange the shares. Every rank
// of the data request takes part whatever it found, so none waits in an
// exchange another has left.
#pragma once

#include "vtkOpalModule.h" // for the export macro

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkMultiProcessController;

namespace vtkOpalRankShares
{
// What a shared step left this rank with.
struct Result
{
  int Shares = 0;       // the ranks that computed what this rank now holds (0: nothing was shared)
  bool Aborted = false; // a rank aborted its share: every rank's request aborts
};

// A share's bytes as they arrive: share `share`'s bytes [first, first + count).
using Sink = std::function<void(int share, std::uint64_t first, std::uint64_t count, const char* bytes)>;
struct Outcome
{
  bool Complete = false; // every share arrived whole (a round: every sharer goes on)
  bool Aborted = false;  // a sharer's share stopped on an abort
};
// A sharer's exchanges. The call sends this rank's share (nullopt: it
// stopped, by an abort where the step's `aborted` says so) and hands every
// share's bytes to `sink` as they arrive: the last exchange. Before it a
// step may take rounds: `round` sends bytes the other sharers need to go on
// (a layer's edge) and hands theirs to `sink`; Complete while every sharer
// goes on. A round that is not complete (a sharer stopped and sent its last)
// ends the exchange: the sharer then calls neither again.
struct Exchanger
{
  std::function<Outcome(const std::optional<std::vector<char>>& mine, const Sink& sink)> Last;
  std::function<Outcome(const std::vector<char>& mine, const Sink& sink)> Round;

  Outcome operator()(const std::optional<std::vector<char>>& mine, const Sink& sink) const
  {
    return this->Last(mine, sink);
  }
  Outcome round(const std::vector<char>& mine, const Sink& sink) const { return this->Round(mine, sink); }
};

// Collective: this rank's part in a shared step, whole. `failed`: this rank
// has failed the request already; otherwise `needs` (none: the rank renders
// nothing) says whether it needs the step, and `layout` (none: always alike)
// how its share's bytes are laid out; an exception from either fails the
// rank and is rethrown once every rank has answered. Where no rank failed
// and two or more need the step, all with one layout (ranks whose devices
// lay a field out differently cannot place each other's bytes: each then
// computes alone), each of them runs `run` with its share (in rank order)
// and the number of shares, which must end the exchange whatever happens:
// its last exchange called exactly once (a failed or aborted share passes
// nullopt) unless a round ended it, so that no rank waits in an exchange
// another has left; the others take part in every round with nothing.
// Throws, naming `what`, where MPI failed (alike on every rank). Shares: the
// sharers' number where `run` returned true.
VTKOPAL_EXPORT Result Share(vtkMultiProcessController* controller, bool failed, const std::function<bool()>& needs,
  const std::function<std::string()>& layout, const std::function<bool()>& aborted, const std::string& what,
  const std::function<bool(int share, int shares, const Exchanger& exchange)>& run);
} // namespace vtkOpalRankShares
