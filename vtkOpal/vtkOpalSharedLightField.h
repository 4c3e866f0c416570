// The light field shared by the ranks of an MPI render (docs/design.md
// §8.1): each rank holds the whole volume, so each could compute the light
// field alone; together each computes a share of the layers' rows and every
// rank holds the whole field, equal bit for bit to one process's. A light low
// or to the side is marched from each voxel, which reads nothing another
// voxel's wrote; a light above is swept layer after layer, each share
// passing the rows at its edges to the shares beside it before the next.
#pragma once

#include "OpalRenderSession.h"
#include "vtkOpalRankShares.h"

#include <functional>

class vtkMultiProcessController;

namespace vtkOpalSharedLightField
{
// Collective over the controller's ranks, as vtkOpalSharedScatteredLight::Solve
// (and before it): where two or more ranks would compute the light field for
// their frames, they compute their shares and each holds the field, which
// its frame then reuses; otherwise nothing happens.
// A shared step's exchanger as the session's per-voxel field steps take it
// (shareLightPass, shareScatteredField): its last exchange, complete or not,
// and its rounds, every share going on or not.
struct SessionExchanges
{
  opal::RenderSession::FieldExchange Last;
  opal::RenderSession::LayerExchange Round;
};
SessionExchanges ForSession(const vtkOpalRankShares::Exchanger& exchange);

vtkOpalRankShares::Result March(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted);
} // namespace vtkOpalSharedLightField
