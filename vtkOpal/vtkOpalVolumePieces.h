// Under MPI the render's input is each rank's piece of the volume
// (docs/design.md §8.1): a rank builds or reads only its piece, and the point
// arrays the render reads are gathered into the whole volume on every rank,
// which each rank renders its piece of the image (the render) or the whole
// stone (the live view's representation) from.
#pragma once

#include "vtkOpalModule.h" // for the export macro
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <string>

class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;

namespace vtkOpalVolumePieces
{
// The ranks are the processes of `controller` (the filter's; none, or one
// process, is one rank holding the whole).
// Asks the input (`inputInformation`, of a request for the update extent)
// for this rank's piece of its whole extent, by extent alone: the whole with
// one process, else the rank's piece of as many as there are ranks (VTK's
// extent translator, as ParaView splits image data), without ghost levels.
VTKOPAL_EXPORT void AskForPiece(vtkMultiProcessController* controller, vtkInformation* inputInformation);

// The whole volume gathered from the ranks' pieces, kept until a rank's piece
// changes: its owner's data request updates it, its frames read it. Its
// point arrays may be released once a device holds their values
// (docs/design.md §8.1).
class VTKOPAL_EXPORT GatheredVolume
{
public:
  // Collective (every rank calls it together): gathers again where any
  // rank's piece (not null; `pieceInformation` its pipeline information,
  // which gives the whole extent) changed since the last Update, or any rank
  // `needsArrays` whose arrays were released, after
  // checking that the whole fits on every rank: the render's point arrays
  // (ScatteringCoefficient, DomainId, SurfaceDistance and, where present,
  // the absorption pair) placed at each piece's extent, with this piece's
  // field data. Nothing to do with one process. Empty, else (alike on every
  // rank) the reason: the whole does not fit, or the pieces differ in an array.
  std::string Update(
    vtkMultiProcessController* controller, vtkImageData* piece, vtkInformation* pieceInformation, bool needsArrays);
  // Drops the gathered point arrays, keeping the geometry and field data (Of
  // still gives the volume, without them); nothing with one process.
  void ReleaseArrays();
  // Whether the volume's arrays were released since it was gathered.
  bool Released() const { return this->ArraysReleased; }
  // The whole volume of `piece`: the piece itself with one process; nullptr
  // where the last Update failed or was given another piece.
  vtkImageData* Of(vtkMultiProcessController* controller, vtkImageData* piece) const;

private:
  vtkSmartPointer<vtkImageData> Volume;
  vtkImageData* From = nullptr; // the piece it was gathered from, in its version
  vtkMTimeType Time = 0;
  bool ArraysReleased = false;
};
} // namespace vtkOpalVolumePieces
