// Command-line flags for every model parameter, named after the source's
// properties in kebab-case (--domain-count, --domain-diameter-range, ...).
// Shared by the command-line programs and the argument fuzzer; no VTK here.
#pragma once

#include "OpalModelParameters.h"

#include <CLI/CLI.hpp>

#include <string>

class OpalModelOptions
{
public:
  // Registers the flags on the app; values land in this object.
  void addTo(CLI::App& app);

  // The parameters: the preset's, then every flag given explicitly.
  opal::ModelParameters parameters() const;
  // The preset to record: custom when --domain-diameter-range overrides it.
  int presetIndex() const;

  const std::string& presetName() const { return this->Preset; }
  double refractiveIndex() const { return this->Parameters.RefractiveIndex; }

private:
  opal::ModelParameters Parameters;
  std::string Preset = "fig12";
  CLI::Option* DomainDiameterRangeOption = nullptr;
};
