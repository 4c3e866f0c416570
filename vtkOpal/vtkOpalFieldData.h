// Records the model's parameters and the placed domain count as field data,
// so a saved volume says how it was made, and the domain table the render reads.
#pragma once

class vtkDataObject;

namespace opal
{
struct ModelParameters;
class DomainLayout;
}

namespace vtkOpalFieldData
{
void AddModelParameters(
  vtkDataObject* data, const opal::ModelParameters& parameters, int preset, int domainsPlaced);

// The domain table the render reads: DomainNormal (float x 3, the (111)
// lattice-plane normal) and DomainParticleDiameter (float, nm), one tuple
// per domain, indexed by DomainId. Every piece carries all of it.
void AddDomainTable(vtkDataObject* data, const opal::DomainLayout& layout);
}
