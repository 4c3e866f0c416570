// Command-line flags for every render parameter, from the render parameters'
// table (OPAL_RENDER_PARAMETERS: --wavelength-step, --mosaic-spread, ...), with
// --width, --height and --rotate-x for one component of a row, and the device's
// flags. No VTK here: the argument fuzzer uses it too.
#pragma once

#include "OpalRenderParameters.h"

#include <CLI/CLI.hpp>

#include <map>
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
  // True if the row's own flag was given.
  bool given(const char* name) const;

  opal::RenderParameters Parameters;
  int DeviceIndex = -1;
  int DeviceMemoryLimit = 0;
  CLI::Option* WidthOption = nullptr;
  CLI::Option* HeightOption = nullptr;
  std::map<std::string, CLI::Option*> RowOptions; // by row name
};
