#include "vtkOpalSharedMarch.h"

#include <exception>
#include <vector>

namespace vtkOpalSharedMarch
{
vtkOpalRankShares::Result Render(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted,
  std::optional<opal::RenderFrame>& rendered)
{
  return vtkOpalRankShares::Share(controller, failed, session ? std::function<bool()>([] { return true; }) : nullptr,
    nullptr, aborted, "the view march's rays", [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
      bool ended = false; // a round that was not complete ended the exchange: no last one then
      const auto round = [&](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
        ended = true; // a throw (MPI failed, alike on every rank) ends it too
        ended = !exchange.round(mine, sink).Complete;
        return !ended;
      };
      std::exception_ptr failure;
      try
      {
        session->shareMarch(opal::RenderSession::MarchShare{ share, shares, round });
        rendered = session->render(frame, progress);
      }
      catch (...)
      {
        failure = std::current_exception();
      }
      session->shareMarch(std::nullopt);
      const bool completed = !failure && rendered && rendered->Status == opal::FrameStatus::Completed;
      if (!ended)
      {
        const auto ignore = [](int, std::uint64_t, std::uint64_t, const char*) {};
        exchange(completed ? std::optional<std::vector<char>>(std::vector<char>{}) : std::nullopt, ignore);
      }
      if (failure)
      {
        std::rethrow_exception(failure);
      }
      return completed;
    });
}
} // namespace vtkOpalSharedMarch
