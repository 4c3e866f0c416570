#include "vtkOpalRankShares.h"

#include "vtkOpalRankAgreement.h"
#include "vtkOpalRankWait.h"

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

// What a sharer says of its share in a round.
enum ShareState : char
{
  ShareFailed = 0,
  ShareDone = 1,
  ShareAborted = 2,
  ShareGoesOn = 3, // a round before the last: its bytes are what the others need to go on
};

// The exchange's rounds: a round of every rank is held at once (4 MiB each),
// beside the shares the sink places (the light field's fields: 44 bytes per
// voxel at most, held whole in 64 MiB rounds, had raised a rank's peak by
// about the whole field).
constexpr vtkIdType ShareRoundBytes = vtkIdType(4) << 20;

// Collective: every rank's answer gathered (Share's `failed`, `needs` and
// `layout`); the sharers in rank order where no rank failed and two or more
// need the step with one layout, else none.
std::vector<int> sharersOf(vtkMultiProcessController* controller, bool failed, const std::function<bool()>& needs,
  const std::function<std::string()>& layout)
{
  namespace agreement = vtkOpalRankAgreement;
  agreement::RankView mine{ {}, failed ? Failed : Bystander, {} };
  std::exception_ptr failure;
  if (!failed && needs)
  {
    try
    {
      mine.Code = needs() ? Sharer : Bystander;
      mine.Settings = mine.Code == Sharer && layout ? layout() : std::string();
    }
    catch (...)
    {
      failure = std::current_exception();
      mine.Code = Failed;
    }
  }
  const std::vector<agreement::RankView> views = agreement::Gather(controller, mine);
  if (failure)
  {
    std::rethrow_exception(failure); // every rank saw this one fail: none exchanges shares
  }
  std::vector<int> sharers;
  bool alike = true;
  for (std::size_t r = 0; r < views.size(); ++r)
  {
    if (views[r].Code == Sharer)
    {
      alike = alike && (sharers.empty() || views[r].Settings == views[static_cast<std::size_t>(sharers.front())].Settings);
      sharers.push_back(static_cast<int>(r));
    }
  }
  return agreement::FirstWith(views, Failed) >= 0 || sharers.size() < 2 || !alike ? std::vector<int>{} : sharers;
}

// This rank's share among `sharers`, or -1.
int shareOf(vtkMultiProcessController* controller, const std::vector<int>& sharers)
{
  const auto share = std::find(sharers.begin(), sharers.end(), vtkOpalRankAgreement::Rank(controller));
  return share == sharers.end() ? -1 : static_cast<int>(share - sharers.begin());
}

// A round's outcome, and whether every sharer goes on to another.
struct Round
{
  Outcome Said;
  bool GoesOn = false;
};

// A rank's word in a round: a sharer's state and the length of its bytes in
// one number (a bystander's: -1), so that a round is two collectives, the
// words and then the bytes (a state's own exchange had made it four).
constexpr vtkIdType StateKinds = 4;
static_assert(sizeof(vtkIdType) == 8, "a word holds a share's length times StateKinds: VTK needs 64-bit ids");
vtkIdType wordOf(const char* state, const std::vector<char>* bytes)
{
  const vtkIdType length = bytes ? static_cast<vtkIdType>(bytes->size()) : 0;
  return state ? length * StateKinds + *state : -1;
}

// Collective over every rank: a round of the exchange. First every rank's
// word (wordOf: `state`, a bystander's nullptr), then the bytes straight from
// `bytes` (a bystander's none), in rounds of ShareRoundBytes: a round's window
// (a round of every rank) is all the exchange holds besides them. Where every
// sharer goes on, each one's bytes go to `sink`; else the shares of those
// done (the last exchange), but not to a sharer that said it goes on (a
// share's bytes are not its edge's).
Round exchangeRound(vtkMultiProcessController* controller, const std::vector<int>& sharers, const char* state,
  const std::vector<char>* bytes, const Sink& sink, const std::string& what)
{
  namespace agreement = vtkOpalRankAgreement;
  const std::vector<vtkIdType> words = agreement::GatherLengths(controller, wordOf(state, bytes));
  std::vector<vtkIdType> lengths(words.size(), 0);
  std::vector<char> states;
  for (std::size_t r = 0; r < words.size(); ++r)
  {
    lengths[r] = std::max<vtkIdType>(words[r], 0) / StateKinds;
  }
  for (const int rank : sharers)
  {
    const vtkIdType word = words[static_cast<std::size_t>(rank)];
    states.push_back(word >= 0 ? static_cast<char>(word % StateKinds) : static_cast<char>(ShareFailed));
  }
  const bool goesOn = std::all_of(states.begin(), states.end(), [](char s) { return s == ShareGoesOn; });
  std::vector<int> shareOfRank(lengths.size(), -1);
  const bool mineGoesOn = state && *state == ShareGoesOn;
  for (std::size_t s = 0; s < sharers.size(); ++s)
  {
    if (goesOn || (!mineGoesOn && states[s] == ShareDone))
    {
      shareOfRank[static_cast<std::size_t>(sharers[s])] = static_cast<int>(s);
    }
  }
  const bool exchanged = agreement::GatherBytesTo(
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
  Round round{ { true, false }, goesOn };
  for (const char s : states)
  {
    round.Said.Complete = round.Said.Complete && (goesOn || s == ShareDone);
    round.Said.Aborted = round.Said.Aborted || s == ShareAborted;
  }
  return round;
}

// A bystander's part: every round, with nothing, until the last.
bool standBy(vtkMultiProcessController* controller, const std::vector<int>& sharers, const std::string& what)
{
  const auto ignore = [](int, std::uint64_t, std::uint64_t, const char*) {};
  Round round;
  do
  {
    round = exchangeRound(controller, sharers, nullptr, nullptr, ignore, what);
  } while (round.GoesOn);
  return round.Said.Aborted;
}
} // namespace

Result Share(vtkMultiProcessController* controller, bool failed, const std::function<bool()>& needs,
  const std::function<std::string()>& layout, const std::function<bool()>& aborted, const std::string& what,
  const std::function<bool(int share, int shares, const Exchanger& exchange)>& run)
{
  if (vtkOpalRankAgreement::Ranks(controller) < 2)
  {
    return {};
  }
  const vtkOpalRankWait::Naming naming("the exchange of " + what);
  const std::vector<int> sharers = sharersOf(controller, failed, needs, layout);
  if (sharers.empty())
  {
    return {};
  }
  const int share = shareOf(controller, sharers);
  if (share < 0)
  {
    return { 0, standBy(controller, sharers, what) };
  }
  Outcome outcome;
  Exchanger exchanger;
  exchanger.Last = [&](const std::optional<std::vector<char>>& mine, const Sink& sink) {
    const char state = mine ? ShareDone : aborted() ? ShareAborted : ShareFailed;
    outcome = exchangeRound(controller, sharers, &state, mine ? &*mine : nullptr, sink, what).Said;
    return outcome;
  };
  exchanger.Round = [&](const std::vector<char>& mine, const Sink& sink) {
    const char state = ShareGoesOn;
    outcome = exchangeRound(controller, sharers, &state, &mine, sink, what).Said;
    return outcome;
  };
  const bool done = run(share, static_cast<int>(sharers.size()), exchanger);
  return { done ? static_cast<int>(sharers.size()) : 0, outcome.Aborted };
}
} // namespace vtkOpalRankShares
