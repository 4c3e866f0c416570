// Under MPI the render's input is each rank's piece of the volume
// (docs/design.md §8.1): a rank builds or reads only its piece, and the point
// arrays the render reads are gathered into the whole volume on every rank,
// which each rank renders its piece of the image (the render) or the whole
// stone (the live view's representation) from.
#pragma once

#include "vtkOpalModule.h" // for the export macro
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <memory>
#include <string>
#include <utility>

class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;
namespace vtkOpalRenderInput
{
struct MediumPiece;
}

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
// (docs/design.md §8.1). A rank of a march shared by the ranks holds only
// the layers of the medium's arrays its device reads (its piece and halo).
class VTKOPAL_EXPORT GatheredVolume
{
public:
  GatheredVolume();
  // Collective (every rank calls it together): gathers again where any
  // rank's piece (not null; `pieceInformation` its pipeline information,
  // which gives the whole extent) changed since the last Update, or any rank
  // `needsArrays` that were released or lack the layers `heldPiece` reads,
  // after checking that what it gathers fits on every rank: the render's
  // point arrays (ScatteringCoefficient, DomainId, SurfaceDistance and, where
  // present, the absorption pair) placed at each piece's extent, with this
  // piece's field data. `heldPiece` (share, shares) is the piece of the
  // volume's layers this rank's device holds (its rank of the ranks for a
  // march shared by them, else one share): for more shares than one the
  // medium's arrays (all but SurfaceDistance) are gathered only for the
  // layers opal::mediumLayersRead names, with the whole medium's sums
  // added up over the ranks. With one process it gathers nothing and drops
  // what it had gathered (its owner now reads its input whole). Empty, else
  // (alike on every rank) the reason: it does not fit, or the pieces differ in an array.
  std::string Update(vtkMultiProcessController* controller, vtkImageData* piece, vtkInformation* pieceInformation,
    bool needsArrays, std::pair<int, int> heldPiece = { 0, 1 });
  // Drops the gathered point arrays, keeping the geometry and field data (Of
  // still gives the volume, without them); nothing with one process.
  void ReleaseArrays();
  // Whether the arrays the render reads for `heldPiece` are held: with one
  // process always; else not once released, nor where the medium's layers
  // gathered lack those the piece reads.
  bool Serves(std::pair<int, int> heldPiece) const;
  // The whole volume of `piece`: the piece itself with one process; nullptr
  // where the last Update failed or was given another piece. Where the
  // medium was gathered by layers it holds SurfaceDistance alone.
  vtkImageData* Of(vtkMultiProcessController* controller, vtkImageData* piece) const;
  // The medium's arrays gathered by layers (nullptr where the volume holds
  // them whole): the layers' image and the whole medium's sums.
  const vtkOpalRenderInput::MediumPiece* Medium() const;
  // The exchange's rounds, in bytes per rank (vtkOpalRankAgreement::RoundBytes;
  // at least 1, else std::invalid_argument): a test's few bytes end rounds
  // within a row and within a value.
  void SetRoundBytes(vtkIdType bytes);

private:
  // Holds nothing gathered (a render with one rank, or a gather begun or failed).
  void Forget();

  vtkSmartPointer<vtkImageData> Volume;
  // Where gathered by layers: the medium's arrays' image (its extent the
  // layers) and the whole medium's sums; else none.
  std::shared_ptr<vtkOpalRenderInput::MediumPiece> MediumLayers;
  vtkImageData* From = nullptr; // the piece it was gathered from, in its version
  vtkMTimeType Time = 0;
  bool ArraysReleased = false;
  vtkIdType RoundBytes; // vtkOpalRankAgreement::RoundBytes unless set
};
} // namespace vtkOpalVolumePieces
