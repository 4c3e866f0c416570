// The view march shared by the ranks of an MPI render (docs/design.md
// §8.1): each rank marches the rays only in its piece of the volume's
// layers z, handing those that leave it to the others between rounds, and
// every rank renders the whole image, whose piece the filter keeps.
#pragma once

#include "OpalRenderSession.h"
#include "vtkOpalRankShares.h"

#include <functional>
#include <optional>

class vtkMultiProcessController;

namespace vtkOpalSharedMarch
{
// Collective over the controller's ranks, as vtkOpalSharedLightField::March:
// where no rank failed and two or more render, each renders `frame` (the
// whole image) with its march shared (RenderSession::shareMarch) into
// `rendered`, the session then marching alone again; otherwise nothing
// happens. A frame that throws is rethrown once the exchange is over.
vtkOpalRankShares::Result Render(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted,
  std::optional<opal::RenderFrame>& rendered);
} // namespace vtkOpalSharedMarch
