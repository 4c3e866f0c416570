// The image output module of opal-render (OpalOutputModules.h): EXR and TIFF
// through OpenImageIO, the format from the extension. Their libraries report
// errors back (libtiff through OpenImageIO's handler, OpenEXR by exceptions
// OpenImageIO catches); JPEG is not written here, as OpenImageIO leaves
// libjpeg's default handler in place, which calls exit() on a full disk.
#include "OpalAtomicFile.h"
#include "OpalOutputModules.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
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

// The fewest decimals that state a wavelength to 1e-9 of itself: finer
// digits are the rounding of lo + i * step (400.29999999999995 is 400.3).
int decimalsNeeded(double wavelength)
{
  int decimals = 0;
  for (double scale = 1.0;
       decimals < 9 && std::abs(std::round(wavelength * scale) / scale - wavelength) > 1e-9 * wavelength;
       scale *= 10.0)
  {
    ++decimals;
  }
  return decimals;
}

// The spectral channels' names: each wavelength in nm with the decimals the
// finest of them needs, so each states its own exactly and they sort in
// wavelength order (EXR keeps channels sorted by name): spectrum.400nm for a
// whole step, spectrum.400,0nm and spectrum.400,5nm for 0.5 nm. The decimal
// separator is a comma, as in the spectral EXR layout of Fichet et al. (JCGT
// 2021): EXR readers split a channel name into layers at its dots.
// Wavelengths lie at least 0.01 nm apart (WavelengthStep), so names differ.
std::vector<std::string> spectralChannelNames(const std::vector<double>& wavelengths)
{
  int decimals = 0;
  for (double wavelength : wavelengths)
  {
    decimals = std::max(decimals, decimalsNeeded(wavelength));
  }
  std::vector<std::string> names;
  for (double wavelength : wavelengths)
  {
    char number[64];
    std::snprintf(number, sizeof(number), "%.*f", decimals, wavelength);
    std::replace(number, number + std::strlen(number), '.', ',');
    names.push_back(std::string("spectrum.") + number + "nm");
  }
  return names;
}

// Whether the file reads back with all its pixels. libtiff reports a
// directory it could not write (a full disk, a file-size limit) only to its
// error handler, and OpenImageIO's close() still returns true for a TIFF cut
// short; OpenEXR's errors are exceptions OpenImageIO turns into failures.
bool readsBackWhole(const std::string& file, const std::string& extension, const OIIO::ImageSpec& spec)
{
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(extension.substr(1));
  OIIO::ImageSpec found;
  if (!in || !in->open(file, found) || found.width != spec.width || found.height != spec.height)
  {
    return false;
  }
  std::vector<float> pixels(found.image_pixels() * static_cast<std::size_t>(found.nchannels));
  return in->read_image(0, 0, 0, found.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()) && in->close();
}

// Writes the spec's pixels through OpenImageIO in the format `extension`
// names (the file's name, from /proc/self/fd, has none); false with the reason.
bool writeWithOpenImageIO(const std::string& file, const std::string& extension, const OIIO::ImageSpec& spec,
  const void* pixels, std::string& reason)
{
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(extension.substr(1));
  if (!out)
  {
    reason = "no OpenImageIO writer: " + OIIO::geterror();
    return false;
  }
  if (!out->open(file, spec))
  {
    reason = out->geterror();
    return false;
  }
  const bool written = out->write_image(spec.format, pixels);
  if (!written)
  {
    reason = out->geterror();
  }
  const bool closed = out->close() && written;
  if (closed && extension != ".exr" && !readsBackWhole(file, extension, spec))
  {
    reason = "the file does not read back whole";
    return false;
  }
  return closed;
}

std::string writeImage(const opal::RenderImage& image, const std::string& path, bool spectralChannels)
{
  const std::string extension = lowerCaseExtension(path);
  const bool exr = extension == ".exr";
  const bool spectral = exr && spectralChannels;
  if (spectral && image.Spectrum.empty())
  {
    return "spectral channels need the Spectrum array";
  }
  std::vector<std::string> names{ "R", "G", "B" };
  const std::size_t extra = spectral ? image.Wavelengths.size() : 0;
  if (spectral)
  {
    const std::vector<std::string> wavelengths = spectralChannelNames(image.Wavelengths);
    names.insert(names.end(), wavelengths.begin(), wavelengths.end());
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
  return writeFileAtomically(path, [&](const std::string& file, std::string& reason) {
    return writeWithOpenImageIO(
      file, extension, spec, exr ? static_cast<const void*>(floats.data()) : bytes.data(), reason);
  });
}

const opal::ImageOutputModule module{ &writeImage };
} // namespace

const opal::ImageOutputModule* opalImageOutputModule()
{
  return &module;
}
