// The image output module of opal-render (OpalOutputModules.h): PNG, EXR and
// the other formats of OpenImageIO, the format from the extension.
#include "OpalAtomicFile.h"
#include "OpalOutputModules.h"

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace
{
// The image's pixels with `channels` values each: `first` (3 per pixel) then,
// if given, `extra` (extraCount per pixel). Rows are top to bottom already.
template <typename T>
std::vector<T> interleave(const std::vector<T>& first, const std::vector<float>& extra, std::size_t extraCount)
{
  const std::size_t pixels = first.size() / 3;
  std::vector<T> out;
  out.reserve(pixels * (3 + extraCount));
  for (std::size_t i = 0; i < pixels; ++i)
  {
    out.insert(out.end(), first.begin() + static_cast<std::ptrdiff_t>(3 * i),
      first.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
    for (std::size_t c = 0; c < extraCount; ++c)
    {
      out.push_back(static_cast<T>(extra[i * extraCount + c]));
    }
  }
  return out;
}

// Writes the spec's pixels through OpenImageIO; false with the reason.
bool writeWithOpenImageIO(const std::string& path, const OIIO::ImageSpec& spec, const void* pixels, std::string& reason)
{
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
  if (!out)
  {
    reason = "no OpenImageIO writer: " + OIIO::geterror();
    return false;
  }
  if (!out->open(path, spec))
  {
    reason = out->geterror();
    return false;
  }
  const bool written = out->write_image(spec.format, pixels);
  if (!written)
  {
    reason = out->geterror();
  }
  return out->close() && written;
}

std::string writeImage(const opal::RenderImage& image, const std::string& path, bool spectralChannels)
{
  const bool exr = lowerCaseExtension(path) == ".exr";
  const bool spectral = exr && spectralChannels;
  if (spectral && image.Spectrum.empty())
  {
    return "spectral channels need the Spectrum array";
  }
  std::vector<std::string> names{ "R", "G", "B" };
  const std::size_t extra = spectral ? image.Wavelengths.size() : 0;
  for (std::size_t i = 0; i < extra; ++i)
  {
    names.push_back("spectrum." + std::to_string(static_cast<int>(image.Wavelengths[i] + 0.5)) + "nm");
  }
  OIIO::ImageSpec spec(image.Region[2], image.Region[3], static_cast<int>(names.size()),
    exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.channelnames = names;
  if (!exr)
  {
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  const std::vector<float> floats = exr ? interleave(image.Radiance, image.Spectrum, extra) : std::vector<float>();
  const std::vector<std::uint8_t> bytes = exr ? std::vector<std::uint8_t>() : interleave(image.RGB, {}, 0);
  std::string reason;
  const std::string error = writeFileAtomically(path, [&](const std::string& temporary) {
    return writeWithOpenImageIO(temporary, spec, exr ? static_cast<const void*>(floats.data()) : bytes.data(), reason);
  });
  return error.empty() ? error : error + (reason.empty() ? "" : " (" + reason + ")");
}

const opal::ImageOutputModule module{ &writeImage };
} // namespace

const opal::ImageOutputModule* opalImageOutputModule()
{
  return &module;
}
