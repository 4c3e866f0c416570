// Command-line flags for every render parameter, named after the render
// filter's properties in kebab-case (--wavelength-step, --mosaic-spread, ...).
// No VTK here: the argument fuzzer uses it too.
#pragma once

#include "OpalRenderParameters.h"

#include <CLI/CLI.hpp>

#include <string>

class OpalRenderOptions
{
public:
  void addTo(CLI::App& app);

  // The parameters: the preset's image size unless given explicitly, the
  // preset's placement of the stone (PresetRotation) under --model-rotation;
  // the refractive index is the model's.
  opal::RenderParameters parameters(const std::string& presetName, double refractiveIndex) const;
  int deviceIndex() const { return this->DeviceIndex; }
  int deviceMemoryLimit() const { return this->DeviceMemoryLimit; }

private:
  void addBraggModelOptions(CLI::App& app);

  opal::RenderParameters Parameters;
  int DeviceIndex = -1;
  int DeviceMemoryLimit = 0;
  CLI::Option* WidthOption = nullptr;
  CLI::Option* HeightOption = nullptr;
  CLI::Option* BraggModelOption = nullptr;
  CLI::Option* LatticePlanesOption = nullptr;
};
