#include "vtkOpalSharedLightField.h"

namespace vtkOpalSharedLightField
{
SessionExchanges ForSession(const vtkOpalRankShares::Exchanger& exchange)
{
  return { [&exchange](const std::optional<std::vector<char>>& mine, const opal::RenderSession::ShareSink& sink) {
            return exchange(mine, sink).Complete;
          },
    [&exchange](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
      return exchange.round(mine, sink).Complete;
    } };
}

vtkOpalRankShares::Result March(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted)
{
  return vtkOpalRankShares::Share(controller, failed,
    session ? std::function<bool()>([&] { return session->needsLightPass(frame); }) : nullptr,
    session ? std::function<std::string()>([&] { return session->lightPassLayout(frame); }) : nullptr, aborted,
    "the light field's shares", [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
      const SessionExchanges exchanges = ForSession(exchange);
      return session->shareLightPass(frame, share, shares, exchanges.Last, exchanges.Round, progress);
    });
}
} // namespace vtkOpalSharedLightField
