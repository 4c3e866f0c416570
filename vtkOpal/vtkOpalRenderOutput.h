// Writes a render's result into VTK image data (docs/design.md §6): the point
// arrays RGB, Radiance, XYZ, DominantBraggWavelength, Depth and Spectrum with
// VTK's rows bottom to top, and the field arrays Wavelengths, Exposure,
// VulkanDevice and RenderTimings. The render filter and the programs' .vti
// output share it.
#pragma once

#include "OpalRenderImage.h"
#include "vtkOpalModule.h" // for export macro

#include <string>

class vtkImageData;

namespace vtkOpalRenderOutput
{
// The image's extent: columns x0 .. x0 + width - 1, and VTK rows counted from
// the bottom of an image ImageSize[1] high.
VTKOPAL_EXPORT void ExtentOf(const opal::RenderImage& image, int extent[6]);

// Replaces `output`'s structure and arrays with the image's.
VTKOPAL_EXPORT void Fill(const opal::RenderImage& image, const std::string& deviceName, vtkImageData* output);
} // namespace vtkOpalRenderOutput
