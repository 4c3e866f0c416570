#include "OpalImageFiles.h"

#include "OpalAtomicFile.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace
{
std::string lowerExtension(const std::string& path)
{
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// Gathers arrays into interleaved pixels, rows top to bottom (VTK's run bottom to top).
template <typename T>
std::vector<T> topDownPixels(vtkImageData* image, const std::vector<vtkDataArray*>& arrays)
{
  int dims[3];
  image->GetDimensions(dims);
  int channels = 0;
  for (vtkDataArray* array : arrays)
  {
    channels += array->GetNumberOfComponents();
  }
  std::vector<T> pixels(static_cast<std::size_t>(dims[0]) * dims[1] * channels);
  std::size_t out = 0;
  for (int row = dims[1] - 1; row >= 0; --row)
  {
    for (int column = 0; column < dims[0]; ++column)
    {
      const vtkIdType id = static_cast<vtkIdType>(row) * dims[0] + column;
      for (vtkDataArray* array : arrays)
      {
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          pixels[out++] = static_cast<T>(array->GetComponent(id, c));
        }
      }
    }
  }
  return pixels;
}
} // namespace

std::string writeRenderedImage(const std::string& path, vtkImageData* image, bool spectralChannels)
{
  int dims[3];
  image->GetDimensions(dims);
  const bool exr = lowerExtension(path) == ".exr";
  vtkPointData* pd = image->GetPointData();
  std::vector<vtkDataArray*> arrays{ pd->GetArray(exr ? "Radiance" : "RGB") };
  std::vector<std::string> names{ "R", "G", "B" };
  if (!arrays[0])
  {
    return "the image has no " + std::string(exr ? "Radiance" : "RGB") + " array";
  }
  if (exr && spectralChannels)
  {
    vtkDataArray* spectrum = pd->GetArray("Spectrum");
    vtkDataArray* wavelengths = image->GetFieldData()->GetArray("Wavelengths");
    if (!spectrum || !wavelengths)
    {
      return "spectral channels need the Spectrum array";
    }
    arrays.push_back(spectrum);
    for (vtkIdType i = 0; i < wavelengths->GetNumberOfTuples(); ++i)
    {
      names.push_back("spectrum." + std::to_string(static_cast<int>(wavelengths->GetComponent(i, 0) + 0.5)) + "nm");
    }
  }
  const int channels = static_cast<int>(names.size());
  OIIO::ImageSpec spec(dims[0], dims[1], channels, exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.channelnames = names;
  if (!exr)
  {
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  std::string reason;
  const std::string error = writeFileAtomically(path, [&](const std::string& temporary) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(temporary);
    if (!out)
    {
      reason = "no OpenImageIO writer for " + path + ": " + OIIO::geterror();
      return false;
    }
    if (!out->open(temporary, spec))
    {
      reason = out->geterror();
      return false;
    }
    bool written;
    if (exr)
    {
      const std::vector<float> pixels = topDownPixels<float>(image, arrays);
      written = out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    }
    else
    {
      const std::vector<std::uint8_t> pixels = topDownPixels<std::uint8_t>(image, arrays);
      written = out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
    }
    if (!written)
    {
      reason = out->geterror();
    }
    return out->close() && written;
  });
  return error.empty() ? error : error + (reason.empty() ? "" : " (" + reason + ")");
}
