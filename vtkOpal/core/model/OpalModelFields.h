// The model parameters a preset may set, by the name they have everywhere
// (docs/design.md §2.8, §6): the source's property and ParaView's, and in
// kebab-case the command-line flag. One table, so that applying a preset
// (OpalModelParameters), filling ParaView's panel (vtkSMOpalVolumeSourceProxy)
// and letting a flag win over a preset (OpalModelOptions) cannot drift apart.
#pragma once

#include "OpalModelParameters.h"

#include <string>
#include <vector>

namespace opal
{

struct ModelField
{
  const char* Property; // "DomainDiameterRange"
  std::vector<double> (*Get)(const ModelParameters&);
  void (*Set)(ModelParameters&, const std::vector<double>&);
};

// Every field a preset may set.
const std::vector<ModelField>& presetModelFields();

// The field of that property name, or nullptr.
const ModelField* presetModelField(const std::string& property);

// "DomainDiameterRange" -> "--domain-diameter-range".
std::string flagOf(const std::string& property);

} // namespace opal
