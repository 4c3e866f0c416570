#include "vtkOpalRankShares.h"

#include "vtkOpalRankAgreement.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <exception>
#include <stdexcept>

namespace vtkOpalRankShares
{
namespace
{
// What each rank brings to the first exchange.
enum ShareCode
{
  Bystander = 0, // renders nothing, or holds what serves its frame
  Sharer = 1,    // needs the step
  Failed = 2,    // has failed the request: no rank exchanges shares
};

// What a sharer says of its share.
enum ShareState : char
{
  ShareFailed = 0,
  ShareDone = 1,
  ShareAborted = 2,
};

// The exchange's rounds: a round of every rank is held at once (4 MiB each),
// beside the shares the sink places (the light field's fields: 44 bytes per
// voxel at most, held whole in 64 MiB rounds, had raised a rank's peak by
// about the whole field).
constexpr vtkIdType ShareRoundBytes = vtkIdType(4) << 20;

// Collective: every rank's answer gathered (Share's `failed` and `needs`);
// the sharers in rank order where no rank failed and two or more need the
// step, else none.
std::vector<int> sharersOf(vtkMultiProcessController* controller, bool failed, const std::function<bool()>& needs)
{
  namespace agreement = vtkOpalRankAgreement;
  int code = failed ? Failed : Bystander;
  std::exception_ptr failure;
  if (!failed && needs)
  {
    try
    {
      code = needs() ? Sharer : Bystander;
    }
    catch (...)
    {
      failure = std::current_exception();
      code = Failed;
    }
  }
  const std::vector<agreement::RankView> views = agreement::Gather(controller, { {}, code, {} });
  if (failure)
  {
    std::rethrow_exception(failure); // every rank saw this one fail: none exchanges shares
  }
  std::vector<int> sharers;
  for (std::size_t r = 0; r < views.size(); ++r)
  {
    if (views[r].Code == Sharer)
    {
      sharers.push_back(static_cast<int>(r));
    }
  }
  return agreement::FirstWith(views, Failed) >= 0 || sharers.size() < 2 ? std::vector<int>{} : sharers;
}

// This rank's share among `sharers`, or -1.
int shareOf(vtkMultiProcessController* controller, const std::vector<int>& sharers)
{
  const auto share = std::find(sharers.begin(), sharers.end(), vtkOpalRankAgreement::Rank(controller));
  return share == sharers.end() ? -1 : static_cast<int>(share - sharers.begin());
}

// Collective over every rank: a sharer sends its share (`mine`), a bystander
// nothing (`mine` nullptr); every share's bytes go to `sink` as they arrive.
Outcome exchange(vtkMultiProcessController* controller, const std::vector<int>& sharers,
  const std::optional<std::vector<char>>* mine, bool aborted, const Sink& sink, const std::string& what)
{
  namespace agreement = vtkOpalRankAgreement;
  // First each sharer's state (a byte; a bystander sends none), then the
  // shares' bytes straight from `mine`, in rounds of ShareRoundBytes: a round's
  // window (a round of every rank) is all the exchange holds besides them.
  const char state = mine && *mine ? ShareDone : aborted ? ShareAborted : ShareFailed;
  const std::vector<vtkIdType> stateLengths = agreement::GatherLengths(controller, mine ? 1 : 0);
  std::vector<char> states;
  const std::vector<char>* bytes = mine && *mine ? &**mine : nullptr;
  const std::vector<vtkIdType> lengths =
    agreement::GatherLengths(controller, bytes ? static_cast<vtkIdType>(bytes->size()) : 0);
  std::vector<int> shareOfRank(lengths.size(), -1);
  for (std::size_t s = 0; s < sharers.size(); ++s)
  {
    shareOfRank[static_cast<std::size_t>(sharers[s])] = static_cast<int>(s);
  }
  const bool exchanged = agreement::GatherBytes(controller, &state, stateLengths, states) &&
    agreement::GatherBytesTo(
      controller, bytes ? bytes->data() : nullptr, lengths,
      [&](int rank, vtkIdType first, vtkIdType count, const char* data) {
        const int share = shareOfRank[static_cast<std::size_t>(rank)];
        if (share >= 0)
        {
          sink(share, static_cast<std::uint64_t>(first), static_cast<std::uint64_t>(count), data);
        }
      },
      ShareRoundBytes);
  if (!exchanged)
  {
    throw std::runtime_error("The ranks could not exchange " + what + ".");
  }
  // A sharer's state is its one byte, at its place among the ranks that sent one.
  const std::vector<vtkIdType> places = agreement::RankOffsets(stateLengths);
  Outcome outcome{ true, false };
  for (const int rank : sharers)
  {
    const std::size_t r = static_cast<std::size_t>(rank);
    const char sent =
      stateLengths[r] > 0 ? states[static_cast<std::size_t>(places[r])] : static_cast<char>(ShareFailed);
    outcome.Complete = outcome.Complete && sent == ShareDone;
    outcome.Aborted = outcome.Aborted || sent == ShareAborted;
  }
  return outcome;
}
} // namespace

Result Share(vtkMultiProcessController* controller, bool failed, const std::function<bool()>& needs,
  const std::function<bool()>& aborted, const std::string& what,
  const std::function<bool(int share, int shares, const Exchanger& exchange)>& run)
{
  if (vtkOpalRankAgreement::Ranks(controller) < 2)
  {
    return {};
  }
  const std::vector<int> sharers = sharersOf(controller, failed, needs);
  if (sharers.empty())
  {
    return {};
  }
  const int share = shareOf(controller, sharers);
  if (share < 0)
  {
    const auto ignore = [](int, std::uint64_t, std::uint64_t, const char*) {};
    return { 0, exchange(controller, sharers, nullptr, false, ignore, what).Aborted };
  }
  Outcome outcome;
  const bool done = run(share, static_cast<int>(sharers.size()),
    [&](const std::optional<std::vector<char>>& mine, const Sink& sink) {
      outcome = exchange(controller, sharers, &mine, aborted(), sink, what);
      return outcome;
    });
  return { done ? static_cast<int>(sharers.size()) : 0, outcome.Aborted };
}
} // namespace vtkOpalRankShares
