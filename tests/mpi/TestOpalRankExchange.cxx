// The ranks' byte exchange under MPI (vtkOpalRankAgreement, docs/design.md
// §8.1), run with mpiexec on 3 ranks: every exchange of the render (the
// agreements' views, the volume's arrays, the every-order tallies) goes
// through GatherBytes, in rounds of at most 64 MiB per rank, which the test
// volumes never fill. Here the rounds are a few bytes, so the pieces cross
// many rounds: uneven lengths (the first rank sends nothing, then the last)
// arrive whole, in rank order, for rounds shorter than, equal to and longer
// than the pieces; the agreements' views arrive likewise.
#include "vtkOpalRankAgreement.h"

#include "vtkMPIController.h"
#include "vtkNew.h"

#include <iostream>
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

bool check(bool condition, const std::string& what, int rank)
{
  if (!condition)
  {
    std::cerr << "rank " << rank << ": FAILED: " << what << std::endl;
  }
  return condition;
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
  // Every rank's verdict: the test fails where any rank's check failed.
  int failures = passed ? 0 : 1, allFailures = 0;
  controller->AllReduce(&failures, &allFailures, 1, vtkCommunicator::SUM_OP);
  if (rank == 0)
  {
    std::cout << "TestOpalRankExchange (" << ranks << " ranks): "
              << (allFailures == 0 ? "all checks passed" : "FAILED on " + std::to_string(allFailures) + " rank(s)")
              << std::endl;
  }
  controller->Finalize();
  return allFailures == 0 ? 0 : 1;
}
