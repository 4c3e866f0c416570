// Under MPI the render's input is each rank's piece of the volume
// (docs/design.md §8.1): a rank builds or reads only its piece, and the point
// arrays the render reads are gathered into the whole volume on every rank,
// which each rank renders its piece of the image from.
#pragma once

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;
class vtkMultiProcessController;

namespace vtkOpalVolumePieces
{
// The ranks are the processes of `controller` (the filter's; none, or one
// process, is one rank holding the whole).
// The piece of `whole` (an extent) this rank asks for: the whole with one
// process, else the rank's piece of as many as there are ranks (VTK's extent
// translator, as ParaView splits image data).
void PieceExtent(vtkMultiProcessController* controller, const int whole[6], int extent[6]);

// Empty where the arrays the render reads of the whole volume `whole` (an
// extent) fit in this machine's memory, else the sentence refusing them.
std::string MemoryError(const int whole[6]);

// Collective (every rank calls it together): the whole volume, `whole`,
// from every rank's piece, with the render's point arrays
// (ScatteringCoefficient, DomainId, SurfaceDistance and, where present, the
// absorption pair) and this piece's field data; the piece itself with one
// process. Empty string, else (on every rank alike) the reason: the ranks'
// pieces differ in an array.
std::string Gather(
  vtkMultiProcessController* controller, vtkImageData* piece, const int whole[6], vtkSmartPointer<vtkImageData>& volume);
} // namespace vtkOpalVolumePieces
