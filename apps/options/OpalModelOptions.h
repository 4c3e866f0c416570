// Command-line flags for every model parameter, from the model parameters'
// table (OPAL_MODEL_PARAMETERS: --domain-count, --domain-diameter-range, ...,
// --seed), with --preset.
// Shared by the command-line programs and the argument fuzzer; no VTK here.
#pragma once

#include "OpalModelFields.h"
#include "OpalModelParameters.h"

#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

class OpalModelOptions
{
public:
  // Registers the flags on the app; values land in this object.
  void addTo(CLI::App& app);

  // The parameters: the preset's, then every flag given explicitly (a flag
  // wins over the preset's value).
  opal::ModelParameters parameters() const;
  // The preset to record: custom when a flag overrides one of its values.
  int presetIndex() const;

  const std::string& presetName() const { return this->Preset; }
  double refractiveIndex() const { return this->Parameters.RefractiveIndex; }

private:
  opal::ModelParameters Parameters;
  // The flags of the values a preset may set (opal::presetModelFields): given
  // explicitly, they win over the preset.
  std::vector<std::pair<CLI::Option*, const opal::ModelField*>> GivenOverPreset;
  std::string Preset = "fig12";
};
