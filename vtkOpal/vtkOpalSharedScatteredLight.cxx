#include "vtkOpalSharedScatteredLight.h"

#include "vtkOpalRankShares.h"
#include "vtkOpalSharedLightField.h"

#include <algorithm>
#include <cstring>

namespace vtkOpalSharedScatteredLight
{
namespace
{
std::optional<std::vector<char>> bytesOf(const std::optional<std::vector<double>>& scores)
{
  if (!scores)
  {
    return std::nullopt;
  }
  std::vector<char> bytes(scores->size() * sizeof(double));
  std::memcpy(bytes.data(), scores->data(), bytes.size());
  return bytes;
}

// The sink that keeps each share's scores (in share order).
vtkOpalRankShares::Sink keepScores(std::vector<std::vector<double>>& scores)
{
  return [&scores](int share, std::uint64_t first, std::uint64_t count, const char* bytes) {
    std::vector<double>& into = scores[static_cast<std::size_t>(share)];
    into.resize(std::max<std::size_t>(into.size(), (first + count) / sizeof(double)));
    std::memcpy(reinterpret_cast<char*>(into.data()) + first, bytes, count);
  };
}
} // namespace

Result Solve(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted)
{
  return vtkOpalRankShares::Share(controller, failed,
    session ? std::function<bool()>([&] { return session->needsScatteredLight(frame); }) : nullptr, nullptr, aborted,
    "the every-order solve's scores", [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
      return session->solveScatteredLightShared(frame, share, shares,
        [&](const std::optional<std::vector<double>>& mine) -> std::optional<std::vector<std::vector<double>>> {
          std::vector<std::vector<double>> scores(static_cast<std::size_t>(shares));
          if (!exchange(bytesOf(mine), keepScores(scores)).Complete)
          {
            return std::nullopt;
          }
          return scores;
        },
        vtkOpalSharedLightField::ForSession(exchange).Round, progress);
    });
}

Result WriteField(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const std::function<bool()>& aborted)
{
  return vtkOpalRankShares::Share(controller, failed,
    session ? std::function<bool()>([&] { return session->needsScatteredField(frame); }) : nullptr,
    session ? std::function<std::string()>([&] { return session->scatteredFieldLayout(); }) : nullptr, aborted, "the every-order field's shares", [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
      const vtkOpalSharedLightField::SessionExchanges exchanges = vtkOpalSharedLightField::ForSession(exchange);
      return session->shareScatteredField(frame, share, shares, exchanges.Last, exchanges.Round);
    });
}
} // namespace vtkOpalSharedScatteredLight
