// The light field marched per voxel shared by the ranks of an MPI render
// (docs/design.md §8.1): each rank holds the whole volume, so each could
// march the light from every voxel alone; together each marches a share of
// the voxels and every rank holds the whole field, equal bit for bit to one
// process's (a voxel's march reads nothing another voxel's wrote).
#pragma once

#include "OpalRenderSession.h"
#include "vtkOpalRankShares.h"

#include <functional>

class vtkMultiProcessController;

namespace vtkOpalSharedLightField
{
// Collective over the controller's ranks, as vtkOpalSharedScatteredLight::Solve
// (and before it): where two or more ranks would march the light per voxel
// for their frames, they march their shares and each holds the field, which
// its frame then reuses; otherwise nothing happens. A light above the grid
// is swept layer after layer by each rank alone.
vtkOpalRankShares::Result March(vtkMultiProcessController* controller, opal::RenderSession* session, bool failed,
  const opal::ResolvedFrame& frame, const opal::RenderProgress& progress, const std::function<bool()>& aborted);
} // namespace vtkOpalSharedLightField
