// The PNG output module of opal-render (OpalOutputModules.h): 8-bit sRGB
// through libpng's simplified API, which loads in a millisecond where
// OpenImageIO's Debian build loads about 260 libraries (0.2 s, a fifth of
// the whole fig12 render). The other formats go through OpenImageIO.
#include "OpalAtomicFile.h"
#include "OpalOutputModules.h"

#include <png.h>

namespace
{
// Writes the image's 8-bit sRGB pixels (rows top to bottom) as a PNG with
// an sRGB chunk; false with libpng's reason.
bool writePng(const std::string& path, const opal::RenderImage& image, std::string& reason)
{
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.Region[2]);
  png.height = static_cast<png_uint_32>(image.Region[3]);
  png.format = PNG_FORMAT_RGB;
  const bool written = png_image_write_to_file(&png, path.c_str(), 0, image.RGB.data(), 0, nullptr) != 0;
  if (!written)
  {
    reason = png.message;
  }
  png_image_free(&png);
  return written;
}

std::string writeImage(const opal::RenderImage& image, const std::string& path, bool /*spectralChannels*/)
{
  return writeFileAtomically(
    path, [&](const std::string& file, std::string& reason) { return writePng(file, image, reason); });
}

const opal::ImageOutputModule module{ &writeImage };
} // namespace

const opal::ImageOutputModule* opalPngOutputModule()
{
  return &module;
}
