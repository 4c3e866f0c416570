// Records the model's parameters and the placed domain count as field data,
// so a saved volume says how it was made.
#pragma once

class vtkDataObject;

namespace opal
{
struct ModelParameters;
}

namespace vtkOpalFieldData
{
void AddModelParameters(
  vtkDataObject* data, const opal::ModelParameters& parameters, int preset, int domainsPlaced);
}
