#include "vtkOpalSharedScatteredLight.h"

#include "vtkOpalRankAgreement.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace vtkOpalSharedScatteredLight
{
namespace
{
// What each rank brings to the first exchange.
enum ShareCode
{
  Bystander = 0, // renders nothing, or holds a field that serves its frame
  Solver = 1,    // needs a new field
  Failed = 2,    // has failed the request: no rank exchanges scores
};

// What a solver sends first in the exchange of scores.
enum ShareState : char
{
  ShareFailed = 0,
  ShareTraced = 1,
  ShareAborted = 2,
};

// The scores every solver sent, in rank order, which is their share order;
// nullopt where a share failed or was aborted (`Aborted` says which).
struct Exchanged
{
  std::optional<std::vector<std::vector<double>>> Scores;
  bool Aborted = false;
};

// Collective: this rank's scores sent (`mine` nullptr: a bystander sends
// nothing; nullopt: its share stopped, `aborted` or failed), every solver's received.
Exchanged exchangeScores(vtkMultiProcessController* controller, const std::vector<int>& solvers,
  const std::optional<std::vector<double>>* mine, bool aborted)
{
  std::vector<char> bytes;
  if (mine)
  {
    bytes.push_back(*mine ? ShareTraced : aborted ? ShareAborted : ShareFailed);
    const std::size_t size = *mine ? (*mine)->size() * sizeof(double) : 0;
    bytes.resize(1 + size);
    if (size > 0)
    {
      std::memcpy(bytes.data() + 1, (*mine)->data(), size);
    }
  }
  const std::vector<vtkIdType> lengths =
    vtkOpalRankAgreement::GatherLengths(controller, static_cast<vtkIdType>(bytes.size()));
  std::vector<char> all;
  if (!vtkOpalRankAgreement::GatherBytes(controller, bytes.data(), lengths, all))
  {
    throw std::runtime_error("The ranks could not exchange the every-order solve's scores.");
  }
  const std::vector<vtkIdType> offsets = vtkOpalRankAgreement::RankOffsets(lengths);
  Exchanged exchanged;
  std::vector<std::vector<double>> scores;
  for (const int rank : solvers)
  {
    const char* sent = all.data() + offsets[rank];
    const char state = lengths[rank] > 0 ? sent[0] : static_cast<char>(ShareFailed);
    exchanged.Aborted = exchanged.Aborted || state == ShareAborted;
    if (state != ShareTraced)
    {
      continue;
    }
    scores.emplace_back(static_cast<std::size_t>(lengths[rank] - 1) / sizeof(double));
    std::memcpy(scores.back().data(), sent + 1, scores.back().size() * sizeof(double));
  }
  if (scores.size() == solvers.size())
  {
    exchanged.Scores = std::move(scores);
  }
  return exchanged;
}
} // namespace

Result Solve(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted)
{
  namespace agreement = vtkOpalRankAgreement;
  if (agreement::Ranks(controller) < 2)
  {
    return {};
  }
  int code = failed ? Failed : Bystander;
  std::exception_ptr failure;
  if (session && !failed)
  {
    try
    {
      code = session->needsScatteredLight(frame) ? Solver : Bystander;
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
    std::rethrow_exception(failure); // every rank saw this one fail: none exchanges scores
  }
  std::vector<int> solvers;
  for (std::size_t r = 0; r < views.size(); ++r)
  {
    if (views[r].Code == Solver)
    {
      solvers.push_back(static_cast<int>(r));
    }
  }
  if (agreement::FirstWith(views, Failed) >= 0 || solvers.size() < 2)
  {
    return {};
  }
  const auto share = std::find(solvers.begin(), solvers.end(), agreement::Rank(controller));
  Exchanged exchanged;
  if (share == solvers.end())
  {
    exchanged = exchangeScores(controller, solvers, nullptr, false);
    return { 0, exchanged.Aborted };
  }
  const bool solved = session->solveScatteredLightShared(frame, static_cast<int>(share - solvers.begin()),
    static_cast<int>(solvers.size()),
    [&](const std::optional<std::vector<double>>& mine) {
      exchanged = exchangeScores(controller, solvers, &mine, aborted());
      return exchanged.Scores;
    },
    progress);
  return { solved ? static_cast<int>(solvers.size()) : 0, exchanged.Aborted };
}
} // namespace vtkOpalSharedScatteredLight
