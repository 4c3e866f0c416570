// Every order's photon solve shared by the ranks of an MPI render
// (docs/design.md §8.1): each rank holds the whole volume, so each could solve
// the scattered light alone; together each traces a share of the photons and
// every rank builds the field from all the shares' scores, equal bit for bit
// to one process's (opal::traceScatteredLightShare).
#pragma once

#include "OpalRenderSession.h"
#include "vtkOpalRankShares.h"

#include <functional>

class vtkMultiProcessController;

namespace vtkOpalSharedScatteredLight
{
// Collective over the controller's ranks: every rank of a data request calls
// it once, between the volume's gather and its frame, whatever it found.
// `session` is this rank's, its volume uploaded for `frame`, or nullptr where
// the rank renders nothing or `failed` the request already. Where two or more
// ranks need a new field, they trace their shares and each holds the field,
// which its frame then reuses; otherwise nothing happens, and a frame that
// needs the field solves it alone. A rank whose share stops where `aborted`
// says so aborts the request on every rank; one whose share fails (it says
// why) leaves the others to solve alone. An exception from the session is
// rethrown only once no rank can wait for this one.
using Result = vtkOpalRankShares::Result;
Result Solve(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted);

// Collective, after Solve, alike: where two or more ranks' frames would write
// the every-order field per voxel from the tally grid they hold (solved
// together or not; on 4 ranks of 2 cores each writing all of it took ~6 s of
// the ~8.5 s every-order stage at 320 x 160 x 400), each writes a share of
// the voxels' rows and every rank holds the whole field, as
// vtkOpalSharedLightField's shares; otherwise nothing happens.
Result WriteField(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const std::function<bool()>& aborted);
} // namespace vtkOpalSharedScatteredLight
