// opal-render: builds the opal volume and renders it spectrally on Vulkan
// compute, writing PNG (sRGB) and/or OpenEXR (linear) images.
#include "OpalCliSupport.h"
#include "OpalImageFiles.h"
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalRenderParameters.h"
#include "OpalRenderOptions.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <vector>

int main(int argc, char** argv)
{
  CLI::App app{ "Builds the volumetric opal model of Nakajima & Kawai and renders it spectrally "
                "(Rayleigh scattering, Bragg diffraction) on Vulkan compute." };
  OpalModelOptions model;
  model.addTo(app);
  OpalRenderOptions render;
  render.addTo(app);
  std::vector<std::string> outputs;
  std::string saveVolume, saveImage;
  bool spectralChannels = false;
  app.add_option("-o,--output", outputs,
       "Image file(s); the format follows the extension: .png sRGB 8-bit, .exr linear float")
    ->group("Output");
  app.add_flag("--exr-spectral-channels", spectralChannels, "Also write one EXR channel per wavelength")
    ->group("Output");
  app.add_option("--save-volume", saveVolume, "Also write the volume as .vti")->group("Output");
  app.add_option("--save-image", saveImage, "Also write the image with all its arrays as .vti")->group("Output");
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return oneLineFailure("opal-render", e.what()); });
  CLI11_PARSE(app, argc, argv);
  if (outputs.empty() && saveImage.empty())
  {
    std::cerr << "opal-render: nothing to write; give -o FILE.png (or .exr) or --save-image FILE.vti" << std::endl;
    return 2;
  }
  // A full disk or a file-size limit then fails the write (and is reported)
  // instead of killing the process half way through a file.
  std::signal(SIGXFSZ, SIG_IGN);
  installStderrOutputWindow("opal-render");
  const auto start = std::chrono::steady_clock::now();

  vtkNew<vtkOpalSource> source;
  source->SetModelParameters(model.parameters());
  source->SetPreset(model.presetIndex());
  vtkNew<vtkOpalSpectralRender> renderer;
  renderer->SetRenderParameters(render.parameters(model.presetName(), model.refractiveIndex()));
  renderer->SetDeviceIndex(render.deviceIndex());
  renderer->SetDeviceMemoryLimit(render.deviceMemoryLimit());
  renderer->SetWriteSpectrum(spectralChannels || !saveImage.empty());
  // Bad parameters cost one line and exit status 2, before any work.
  for (const std::string& error : { opal::validate(source->GetModelParameters()),
         opal::validate(renderer->GetRenderParameters()) })
  {
    if (!error.empty())
    {
      std::cerr << "opal-render: " << error << std::endl;
      return 2;
    }
  }
  renderer->SetInputConnection(source->GetOutputPort(0));
  showProgress(source, "volume");
  showProgress(renderer, "render");
  if (!renderer->GetExecutive()->Update())
  {
    std::cerr << "opal-render: rendering failed." << std::endl;
    return 1;
  }
  vtkImageData* image = renderer->GetOutput();

  std::vector<std::string> written;
  auto record = [&](const std::string& path, const std::string& error) {
    if (!error.empty())
    {
      std::cerr << "opal-render: " << error << std::endl;
      return false;
    }
    written.push_back(path);
    return true;
  };
  for (const std::string& path : outputs)
  {
    if (!record(path, writeRenderedImage(path, image, spectralChannels)))
    {
      return 1;
    }
  }
  if (!saveImage.empty() && !record(saveImage, writeImageDataFile(saveImage, image)))
  {
    return 1;
  }
  if (!saveVolume.empty() && !record(saveVolume, writeImageDataFile(saveVolume, source->GetOutput())))
  {
    return 1;
  }

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkFieldData* fd = image->GetFieldData();
  vtkDataArray* timings = fd->GetArray("RenderTimings");
  int dims[3];
  image->GetDimensions(dims);
  std::printf("Opal render (preset %s): %d x %d pixels, %lld wavelengths on %s\n", model.presetName().c_str(),
    dims[0], dims[1], static_cast<long long>(fd->GetArray("Wavelengths")->GetNumberOfTuples()),
    vtkStringArray::SafeDownCast(fd->GetAbstractArray("VulkanDevice"))->GetValue(0).c_str());
  std::printf("  render: setup %.3f s, upload %.3f s, light pass %.3f s, march %.3f s, colour %.3f s, "
              "readback %.3f s\n",
    timings->GetComponent(0, 0), timings->GetComponent(0, 1), timings->GetComponent(0, 2),
    timings->GetComponent(0, 3), timings->GetComponent(0, 4), timings->GetComponent(0, 5));
  std::printf("  exposure %.4g, total %.3f s\n", fd->GetArray("Exposure")->GetComponent(0, 0), seconds);
  for (const std::string& path : written)
  {
    std::printf("  written: %s\n", path.c_str());
  }
  return 0;
}
