// Reads what the render needs from an Opal volume (docs/design.md §2, §6):
// the voxel fields (three, and the absorption where present) without a
// virtual call per value (the arrays' own memory where they are float/int
// AOS arrays, else one converted copy), the domain table from the field data
// the source writes, and the render settings the source records in its
// output information.
#pragma once

#include "OpalModelParameters.h"
#include "OpalRenderFrame.h"
#include "OpalRenderParameters.h"
#include "OpalRenderVolume.h"

#include "vtkImageData.h" // for the medium's arrays' image
#include "vtkSmartPointer.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkImageData;
class vtkInformation;

namespace vtkOpalRenderInput
{
// Holds converted copies where an input array is not of the render's type.
struct Storage
{
  std::vector<float> Scattering, SurfaceDistance, Absorption, AbsorptionExponent;
  std::vector<std::int32_t> DomainId;
};

// The medium's arrays of some layers z alone (a rank of a march shared by
// the ranks, docs/design.md §8.1): `Arrays`, an image of the whole's x and y
// and those layers, holds ScatteringCoefficient, DomainId and the absorption
// pair; `Held` names the layers and the whole medium's sums.
struct MediumPiece
{
  vtkSmartPointer<vtkImageData> Arrays;
  opal::HeldMedium Held;
};

// Fills `volume` from the input image (the medium's arrays from `medium`
// where given); returns an empty string or the reason it cannot (naming the array).
std::string Read(vtkImageData* input, opal::RenderVolume& volume, Storage& storage, const MediumPiece* medium = nullptr);

// What the volume implies for its render (opal::renderHints): the upstream
// vtkOpalSource's RENDER_HINTS in the input information. Without it (a
// volume read from a file) the hints of the volume's field data (Preset,
// RefractiveIndex) when `volume` is given, but the render's default image
// size (it is needed before any data exists).
using VolumeSettings = opal::VolumeRenderHints;
VolumeSettings ReadSettings(vtkInformation* inputInformation, vtkImageData* volume = nullptr);
} // namespace vtkOpalRenderInput
