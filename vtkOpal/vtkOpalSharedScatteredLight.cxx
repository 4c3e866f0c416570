#include "vtkOpalSharedScatteredLight.h"

#include "vtkOpalRankAgreement.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <numeric>

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

// Collective: this rank's scores sent (`mine` nullptr: a bystander sends
// nothing; nullopt: its share failed), every solver's received in rank order,
// which is their share order; nullopt where any solver's share failed.
std::optional<std::vector<std::vector<double>>> exchangeScores(vtkMultiProcessController* controller,
  const std::vector<int>& solvers, const std::optional<std::vector<double>>* mine)
{
  std::vector<char> bytes;
  if (mine)
  {
    bytes.push_back(*mine ? 1 : 0);
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
    return std::nullopt;
  }
  std::vector<vtkIdType> offsets(lengths.size(), 0);
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  std::vector<std::vector<double>> scores;
  for (const int rank : solvers)
  {
    const char* sent = all.data() + offsets[rank];
    if (lengths[rank] < 1 || sent[0] != 1)
    {
      return std::nullopt;
    }
    scores.emplace_back(static_cast<std::size_t>(lengths[rank] - 1) / sizeof(double));
    std::memcpy(scores.back().data(), sent + 1, scores.back().size() * sizeof(double));
  }
  return scores;
}
} // namespace

int Solve(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress)
{
  namespace agreement = vtkOpalRankAgreement;
  if (agreement::Ranks(controller) < 2)
  {
    return 0;
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
    return 0;
  }
  const auto share = std::find(solvers.begin(), solvers.end(), agreement::Rank(controller));
  if (share == solvers.end())
  {
    exchangeScores(controller, solvers, nullptr);
    return 0;
  }
  const bool solved = session->solveScatteredLightShared(frame, static_cast<int>(share - solvers.begin()),
    static_cast<int>(solvers.size()),
    [&](const std::optional<std::vector<double>>& mine) { return exchangeScores(controller, solvers, &mine); },
    progress);
  return solved ? static_cast<int>(solvers.size()) : 0;
}
} // namespace vtkOpalSharedScatteredLight
