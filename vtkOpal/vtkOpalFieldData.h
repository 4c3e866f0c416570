// Records the model's parameters and the placed domain count as field data,
// so a saved volume says how it was made, and the domain table the render reads.
#pragma once

class vtkDataObject;
class vtkFieldData;

namespace opal
{
struct ModelParameters;
class DomainLayout;
}

namespace vtkOpalFieldData
{
// One array per row of the model parameters' table, named as the row (int
// rows as vtkIntArray, double rows as vtkDoubleArray), the Preset's name and
// DomainsPlaced.
void AddModelParameters(
  vtkDataObject* data, const opal::ModelParameters& parameters, int preset, int domainsPlaced);

// The model parameters the field data records: each row's array where it has
// the row's component count, the default where it is missing.
opal::ModelParameters ReadModelParameters(vtkFieldData* fields);

// The domain table the render reads: DomainNormal (float x 3, the (111)
// lattice-plane normal) and DomainParticleDiameter (float, nm), one tuple
// per domain, indexed by DomainId. Every piece carries all of it.
void AddDomainTable(vtkDataObject* data, const opal::DomainLayout& layout);
}
