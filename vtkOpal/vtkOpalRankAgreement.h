// Under MPI the ranks of one render agree before and after it
// (docs/design.md §8.1): each rank's view is gathered to every rank, so all
// take the same path and say the same, and none waits in an exchange that
// another has left (every rank of a data request calls both, whatever it found).
#pragma once

#include "vtkOpalModule.h" // for the export macro
#include "vtkType.h"

#include <functional>
#include <string>
#include <vector>

class vtkMultiProcessController;

namespace vtkOpalRankAgreement
{
// What a rank brings: its settings, one "Name value..." line per parameter
// (compared), and its state, a code (the caller's; 0 fine) with the sentence
// that says why.
struct RankView
{
  std::string Settings;
  int Code = 0;
  std::string Message;
};

// The ranks are the processes of `controller` (the filter's; none, or one
// process, is a rank of its own).
// This rank's number and the number of ranks.
int Rank(vtkMultiProcessController* controller);
int Ranks(vtkMultiProcessController* controller);

// Collective, over the controller's processes (more than one): every rank's
// `mine`, in rank order. Throws where the exchange failed (alike on every rank).
VTKOPAL_EXPORT std::vector<vtkIdType> GatherLengths(vtkMultiProcessController* controller, vtkIdType mine);
// Collective, likewise: every rank's `count` ints from `mine`, in rank order
// (`what` they are names a failed exchange).
std::vector<int> GatherInts(vtkMultiProcessController* controller, const int* mine, int count, const char* what);
// Collective, likewise: every rank's `lengths[r]` bytes from `mine` into
// `bytes` (the ranks' bytes one after another), in rounds of at most
// `roundBytes` (64 MiB) per rank: MPI's counts and displacements are ints.
// False where an exchange failed (alike on every rank).
constexpr vtkIdType RoundBytes = vtkIdType(64) << 20;
VTKOPAL_EXPORT bool GatherBytes(vtkMultiProcessController* controller, const char* mine,
  const std::vector<vtkIdType>& lengths, std::vector<char>& bytes, vtkIdType roundBytes = RoundBytes);
// GatherBytes with each round handed to `sink` as it arrives (rank r's bytes
// [first, first + count) at `data`) instead of kept: a caller that places
// them holds one round, not every rank's bytes. To every rank, or where
// `destination` is a rank to it alone (the others' sinks are not called).
using ByteSink = std::function<void(int rank, vtkIdType first, vtkIdType count, const char* data)>;
VTKOPAL_EXPORT bool GatherBytesTo(vtkMultiProcessController* controller, const char* mine,
  const std::vector<vtkIdType>& lengths, const ByteSink& sink, vtkIdType roundBytes = RoundBytes,
  int destination = -1);
// Where each rank's bytes begin in GatherBytes's `bytes`, from its `lengths`.
std::vector<vtkIdType> RankOffsets(const std::vector<vtkIdType>& lengths);

// Every rank's view, in rank order: this rank's alone with one process.
std::vector<RankView> Gather(vtkMultiProcessController* controller, const RankView& mine);

// Empty where every rank's settings equal rank 0's; else one sentence naming
// the first parameter in which a rank differs, with both values.
std::string SettingsDisagreement(const std::vector<RankView>& views);

// A parameter's line in a RankView's settings: "Name value...", each value
// in the shortest text that reads back as it.
std::string SettingsLine(const char* name, const std::vector<double>& values);

// True on every rank where any rank's `mine` is true.
bool AnyRank(vtkMultiProcessController* controller, bool mine);
// The largest of the ranks' `mine`, on every rank.
int MostOverRanks(vtkMultiProcessController* controller, int mine);

// The first rank (from 0) whose code is `code`, or -1.
int FirstWith(const std::vector<RankView>& views, int code);
} // namespace vtkOpalRankAgreement
