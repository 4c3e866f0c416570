// Command-line flags for every render parameter, named after the render
// filter's properties in kebab-case (--wavelength-step, --mosaic-spread, ...).
#pragma once

#include "OpalRenderParameters.h"

#include <CLI/CLI.hpp>

#include <string>

class vtkOpalSpectralRender;

class OpalRenderOptions
{
public:
  void addTo(CLI::App& app);

  // Configures the filter: the preset's image size and rotation unless given
  // explicitly; the refractive index is the model's.
  void configure(vtkOpalSpectralRender* render, const std::string& presetName, double refractiveIndex) const;

private:
  opal::RenderParameters Parameters;
  int DeviceIndex = -1;
  int DeviceMemoryLimit = 0;
  CLI::Option* WidthOption = nullptr;
  CLI::Option* HeightOption = nullptr;
  CLI::Option* RotateXOption = nullptr;
  CLI::Option* ModelRotationOption = nullptr;
};
