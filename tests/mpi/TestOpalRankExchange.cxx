// The ranks' byte exchange under MPI (vtkOpalRankAgreement, docs/design.md
// §8.1), run with mpiexec on 3 ranks: every exchange of the render (the
// agreements' views, the volume's arrays, the every-order tallies) goes
// through GatherBytes, in rounds of at most 64 MiB per rank, which the test
// volumes never fill. Here the rounds are a few bytes, so the pieces cross
// many rounds: uneven lengths (the first rank sends nothing, then the last)
// arrive whole, in rank order, for rounds shorter than, equal to and longer
// than the pieces; the agreements' views arrive likewise. A shared step
// (vtkOpalRankShares::Share) takes its rounds and its last exchange alike on
// every rank; a sharer that stops ends every rank's rounds in that round;
// ranks whose shares would be laid out differently share nothing. The
// exchanges' bound (vtkOpalRankWait) reads its limit from the environment:
// seconds as given, 0 for none, the default where unset or not a number of
// seconds at least 0 (its end of a job is TestOpalMPIAgreement's).
#include "OpalRankVerdict.h"
#include "vtkOpalRankAgreement.h"
#include "vtkOpalRankShares.h"
#include "vtkOpalRankWait.h"

#include "vtkMPIController.h"
#include "vtkNew.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace
{
// Rank r's bytes: `order` * 1250 of them, a pattern of the rank and the index.
std::vector<char> bytesOf(int rank, int order)
{
  std::vector<char> bytes(static_cast<std::size_t>(order) * 1250);
  for (std::size_t i = 0; i < bytes.size(); ++i)
  {
    bytes[i] = static_cast<char>((rank * 31 + i * 7) % 251);
  }
  return bytes;
}

// The limit each value of OPAL_EXCHANGE_WAIT_LIMIT gives (nullptr: unset).
bool checkWaitLimit(int rank)
{
  namespace wait = vtkOpalRankWait;
  const std::vector<std::pair<const char*, double>> cases = { { nullptr, wait::DefaultLimitSeconds },
    { "", wait::DefaultLimitSeconds }, { "2.5", 2.5 }, { "0", 0 }, { "-1", wait::DefaultLimitSeconds },
    { "ten", wait::DefaultLimitSeconds }, { "5s", wait::DefaultLimitSeconds }, { "inf", wait::DefaultLimitSeconds } };
  bool passed = true;
  for (const auto& [text, limit] : cases)
  {
    if (text)
    {
      setenv(wait::LimitVariable, text, 1);
    }
    else
    {
      unsetenv(wait::LimitVariable);
    }
    if (wait::LimitSeconds() != limit)
    {
      std::cerr << "rank " << rank << ": " << wait::LimitVariable << "=" << (text ? text : "(unset)") << " gives "
                << wait::LimitSeconds() << " s, not " << limit << std::endl;
      passed = false;
    }
  }
  unsetenv(wait::LimitVariable);
  return passed;
}

bool check(bool condition, const std::string& what, int rank)
{
  if (!condition)
  {
    std::cerr << "rank " << rank << ": FAILED: " << what << std::endl;
  }
  return condition;
}

// How a shared step of the test ends.
enum class Step
{
  Whole,     // every share takes three rounds, then its last exchange
  Stops,     // share 1 sends its last (nothing) after its first round
  Unalike,   // rank 1's share would be laid out otherwise
};

// Share `share`'s rounds and last exchange: every round's bytes of every share
// checked as they arrive; true where the last exchange was complete.
bool runShare(int share, int shares, const vtkOpalRankShares::Exchanger& exchange, Step step, bool& passed, int rank)
{
  std::vector<std::vector<char>> got;
  const auto keep = [&got](int from, std::uint64_t first, std::uint64_t count, const char* bytes) {
    std::vector<char>& into = got[static_cast<std::size_t>(from)];
    into.resize(std::max<std::size_t>(into.size(), first + count));
    std::memcpy(into.data() + first, bytes, count);
  };
  for (int round = 0; round < 3; ++round)
  {
    if (step == Step::Stops && share == 1 && round == 1)
    {
      exchange(std::nullopt, keep);
      return false;
    }
    got.assign(static_cast<std::size_t>(shares), {});
    const bool goesOn = exchange.round(bytesOf(share + round, share + 1), keep).Complete;
    if (!goesOn)
    {
      passed = check(step == Step::Stops && round == 1, "a round ends only where a sharer stopped", rank) && passed;
      return false;
    }
    for (int from = 0; from < shares; ++from)
    {
      passed = check(got[static_cast<std::size_t>(from)] == bytesOf(from + round, from + 1),
                 "round " + std::to_string(round) + ": share " + std::to_string(from) + "'s bytes", rank) &&
        passed;
    }
  }
  got.assign(static_cast<std::size_t>(shares), {});
  const bool complete = exchange(bytesOf(share, 2), keep).Complete;
  for (int from = 0; from < shares; ++from)
  {
    passed = check(got[static_cast<std::size_t>(from)] == bytesOf(from, 2),
               "the last exchange: share " + std::to_string(from) + "'s bytes", rank) && passed;
  }
  return complete;
}

bool checkShare(vtkMultiProcessController* controller, int rank, int ranks)
{
  bool passed = true;
  for (const Step step : { Step::Whole, Step::Stops, Step::Unalike })
  {
    const std::string layout = step == Step::Unalike && rank == 1 ? "16 bytes per voxel; " : "8 bytes per voxel; ";
    bool ran = false;
    const vtkOpalRankShares::Result result = vtkOpalRankShares::Share(
      controller, false, [] { return true; }, [&layout] { return layout; }, [] { return false; }, "the test's shares",
      [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
        ran = true;
        return runShare(share, shares, exchange, step, passed, rank);
      });
    const char* name = step == Step::Whole ? "whole" : step == Step::Stops ? "a sharer stopping" : "unalike layouts";
    passed = check(ran == (step != Step::Unalike), std::string(name) + ": who runs a share", rank) && passed;
    passed = check(result.Shares == (step == Step::Whole ? ranks : 0) && !result.Aborted,
               std::string(name) + ": the shares counted", rank) &&
      passed;
  }
  return passed;
}
} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  const int rank = controller->GetLocalProcessId(), ranks = controller->GetNumberOfProcesses();
  bool passed = check(ranks >= 2, "runs on two or more ranks", rank);
  // Lengths rising with the rank (the first sends nothing), then falling (the last sends nothing).
  for (const bool rising : { true, false })
  {
    auto order = [&](int r) { return rising ? r : ranks - 1 - r; };
    std::vector<char> expected;
    for (int r = 0; r < ranks; ++r)
    {
      const std::vector<char> piece = bytesOf(r, order(r));
      expected.insert(expected.end(), piece.begin(), piece.end());
    }
    const std::vector<char> mine = bytesOf(rank, order(rank));
    const std::vector<vtkIdType> lengths =
      vtkOpalRankAgreement::GatherLengths(controller, static_cast<vtkIdType>(mine.size()));
    for (int r = 0; r < ranks; ++r)
    {
      passed = check(lengths[r] == order(r) * 1250, "rank " + std::to_string(r) + "'s length", rank) && passed;
    }
    for (const vtkIdType round : { vtkIdType(1), vtkIdType(7), vtkIdType(1250), vtkIdType(4096),
           vtkOpalRankAgreement::RoundBytes })
    {
      std::vector<char> bytes;
      const bool exchanged = vtkOpalRankAgreement::GatherBytes(controller, mine.data(), lengths, bytes, round);
      passed = check(exchanged && bytes == expected,
                 "every rank's bytes, whole and in rank order, in rounds of " + std::to_string(round) +
                   (rising ? " (the first rank empty)" : " (the last rank empty)"),
                 rank) &&
        passed;
    }
    // To one rank alone: each rank in turn receives every rank's bytes, the others nothing.
    const std::vector<vtkIdType> offsets = vtkOpalRankAgreement::RankOffsets(lengths);
    for (int to = 0; to < ranks; ++to)
    {
      for (const vtkIdType round : { vtkIdType(7), vtkOpalRankAgreement::RoundBytes })
      {
        std::vector<char> bytes(expected.size(), 0);
        bool called = false;
        const bool exchanged = vtkOpalRankAgreement::GatherBytesTo(controller, mine.data(), lengths,
          [&](int from, vtkIdType first, vtkIdType count, const char* data) {
            called = true;
            std::copy_n(data, count, bytes.data() + offsets[from] + first);
          },
          round, to);
        passed = check(exchanged && (rank == to ? bytes == expected : !called),
                   "to rank " + std::to_string(to) + " alone in rounds of " + std::to_string(round) +
                     ": every rank's bytes there, none elsewhere",
                   rank) &&
          passed;
      }
    }
  }
  const std::vector<vtkOpalRankAgreement::RankView> views = vtkOpalRankAgreement::Gather(
    controller, { "Setting " + std::to_string(rank) + "\n", rank + 10, "message of rank " + std::to_string(rank) });
  for (int r = 0; r < ranks; ++r)
  {
    const bool same = views.size() == static_cast<std::size_t>(ranks) && views[r].Code == r + 10 &&
      views[r].Message == "message of rank " + std::to_string(r) &&
      views[r].Settings == "Setting " + std::to_string(r) + "\n";
    passed = check(same, "rank " + std::to_string(r) + "'s view", rank) && passed;
  }
  passed = checkShare(controller, rank, ranks) && passed;
  passed = checkWaitLimit(rank) && passed;
  const int status = opaltest::rankVerdict(controller, passed, "TestOpalRankExchange");
  controller->Finalize();
  return status;
}
