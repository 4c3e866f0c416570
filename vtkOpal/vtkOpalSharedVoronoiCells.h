// The Voronoi cells assigned by the ranks of an MPI build together
// (docs/design.md §2.9, §8.1): a rank's layout needs the cell of every voxel
// of the grid, whatever its piece (which cells are ordered follows from all
// of their faces), so every rank assigned the whole grid. Together each
// assigns a share of the grid's layers and all exchange their runs, which
// stack into the one-process runs bit for bit.
#pragma once

#include "OpalDomainLayout.h"
#include "vtkOpalRankShares.h"

#include <functional>
#include <optional>
#include <string>

class vtkMultiProcessController;

namespace vtkOpalSharedVoronoiCells
{
// Collective over the controller's ranks that build a new Voronoi layout
// (every rank of the update after a change of the settings, as ParaView
// updates them): `failed` where this rank has refused its request. Where two
// or more ranks with the same model settings build it, each assigns its
// share of the layers and `layout` holds the layout; otherwise `layout` is
// left empty and the caller builds alone. Aborted: a rank aborted its share,
// and every rank's request aborts.
// The model settings as the ranks compare them (a line per model
// parameter): ranks share only where theirs are equal.
std::string SettingsOf(const opal::ModelParameters& parameters);

vtkOpalRankShares::Result Build(vtkMultiProcessController* controller, bool failed,
  const opal::ModelParameters& parameters, const std::function<bool(double)>& progress,
  const std::function<bool()>& aborted, std::optional<opal::DomainLayout>& layout);
} // namespace vtkOpalSharedVoronoiCells
