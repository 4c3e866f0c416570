// Writes a rendered image through OpenImageIO, the format from the extension:
// .exr linear float Radiance (optionally one extra channel per wavelength);
// any other (.png, .tif, .jpg ...) the 8-bit sRGB RGB array.
#pragma once

#include <string>

class vtkImageData;

// Returns an empty string on success, else the reason. Writes to a temporary
// name and renames, so an earlier file is never replaced by a partial one.
std::string writeRenderedImage(const std::string& path, vtkImageData* image, bool spectralChannels);
