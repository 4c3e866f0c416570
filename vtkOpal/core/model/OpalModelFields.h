// The model parameters a preset may set (docs/design.md §2.8, §6): the rows
// of the model parameters' table (OPAL_MODEL_PARAMETERS) that presets fill, so
// that applying a preset (OpalModelParameters), filling ParaView's panel
// (vtkSMOpalVolumeSourceProxy) and letting a flag win over a preset
// (OpalModelOptions) cannot drift apart.
#pragma once

#include "OpalModelParameters.h"

#include <string>
#include <vector>

namespace opal
{

using ModelField = ParameterRow<ModelParameters>;

// Every row a preset may set.
const std::vector<ModelField>& presetModelFields();

// The row of that name among them, or nullptr.
const ModelField* presetModelField(const std::string& property);

} // namespace opal
