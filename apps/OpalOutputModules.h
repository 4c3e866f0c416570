// opal-render's file output lives in plugin libraries, loaded only when a
// file of their kind is written, so the program itself starts without them:
// PNG through libpng, JPEG through libjpeg, the other images through
// OpenImageIO (Debian's build loads ~260 libraries, 0.2 s) and .vti through
// VTK. Each writer's errors come back to the caller: none ends the process. Each module exports one C function
// returning its table of functions.
#pragma once

#include "OpalModelParameters.h"
#include "OpalRenderImage.h"

#include <string>

namespace opal
{

struct ImageOutputModule
{
  // Writes the image in the format of the path's extension: .exr linear float
  // Radiance (and one channel per wavelength with spectralChannels), else the
  // 8-bit sRGB RGB. Empty on success, else the reason.
  std::string (*WriteImage)(const RenderImage& image, const std::string& path, bool spectralChannels);
};

struct VtiOutputModule
{
  // Writes the rendered image with all its arrays as .vti.
  std::string (*WriteImage)(const RenderImage& image, const std::string& deviceName, const std::string& path);
  // Builds the volume with the VTK source (the arrays ParaView shows) and writes it as .vti.
  std::string (*WriteVolume)(const ModelParameters& parameters, int preset, const std::string& path);
};

// The modules, loaded on first use from the library folder beside the
// program's (../lib/); throw std::runtime_error naming the file if they
// cannot be loaded. The image module for a path: libpng's for .png,
// libjpeg's for .jpg and .jpeg (any case), OpenImageIO's for the others.
const ImageOutputModule& imageOutputModule(const std::string& path);
const VtiOutputModule& vtiOutputModule();

} // namespace opal

// What each module exports.
extern "C" const opal::ImageOutputModule* opalImageOutputModule();
extern "C" const opal::ImageOutputModule* opalPngOutputModule();
extern "C" const opal::ImageOutputModule* opalJpegOutputModule();
extern "C" const opal::VtiOutputModule* opalVtiOutputModule();
