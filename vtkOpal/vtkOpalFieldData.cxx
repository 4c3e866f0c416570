#include "vtkOpalFieldData.h"

#include "OpalDomainLayout.h"
#include "OpalModelParameters.h"
#include "OpalPresets.h"

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include <initializer_list>

namespace
{
template <typename ArrayT, typename T>
void addArray(vtkFieldData* fieldData, const char* name, std::initializer_list<T> values)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  for (T value : values)
  {
    array->InsertNextValue(value);
  }
  fieldData->AddArray(array);
}
} // namespace

namespace vtkOpalFieldData
{
void AddModelParameters(
  vtkDataObject* data, const opal::ModelParameters& p, int preset, int domainsPlaced)
{
  vtkFieldData* f = data->GetFieldData();
  addArray<vtkIntArray>(f, "Dimensions", { p.Dimensions[0], p.Dimensions[1], p.Dimensions[2] });
  addArray<vtkDoubleArray>(f, "PhysicalSize", { p.PhysicalSize[0], p.PhysicalSize[1], p.PhysicalSize[2] });
  addArray<vtkDoubleArray>(f, "SemiAxes", { p.SemiAxes[0], p.SemiAxes[1], p.SemiAxes[2] });
  addArray<vtkDoubleArray>(
    f, "ScatteringDiameterRange", { p.ScatteringDiameterRange[0], p.ScatteringDiameterRange[1] });
  addArray<vtkDoubleArray>(f, "ScatteringVolumeFraction", { p.ScatteringVolumeFraction });
  addArray<vtkIntArray>(f, "DomainCount", { p.DomainCount });
  addArray<vtkIntArray>(f, "DomainVertexRange", { p.DomainVertexRange[0], p.DomainVertexRange[1] });
  addArray<vtkDoubleArray>(f, "DomainRadiusRange", { p.DomainRadiusRange[0], p.DomainRadiusRange[1] });
  addArray<vtkDoubleArray>(f, "DomainVertexJitter", { p.DomainVertexJitter[0], p.DomainVertexJitter[1] });
  addArray<vtkDoubleArray>(f, "DomainAngleRange", { p.DomainAngleRange[0], p.DomainAngleRange[1] });
  addArray<vtkDoubleArray>(
    f, "DomainRotationRange", { p.DomainRotationRange[0], p.DomainRotationRange[1] });
  addArray<vtkDoubleArray>(
    f, "DomainDiameterRange", { p.DomainDiameterRange[0], p.DomainDiameterRange[1] });
  addArray<vtkIntArray>(f, "DomainLayout", { static_cast<int>(p.DomainLayout) });
  addArray<vtkIntArray>(f, "VoronoiCellCount", { p.VoronoiCellCount });
  addArray<vtkDoubleArray>(f, "VoronoiWeightSpread", { p.VoronoiWeightSpread });
  addArray<vtkDoubleArray>(f, "OrderedFraction", { p.OrderedFraction });
  addArray<vtkDoubleArray>(f, "DiameterCorrelationLength", { p.DiameterCorrelationLength });
  addArray<vtkDoubleArray>(f, "BodyAbsorption", { p.BodyAbsorption });
  addArray<vtkDoubleArray>(f, "BodyAbsorptionExponent", { p.BodyAbsorptionExponent });
  addArray<vtkDoubleArray>(f, "BackingThickness", { p.BackingThickness });
  addArray<vtkDoubleArray>(f, "BackingAbsorption", { p.BackingAbsorption });
  addArray<vtkDoubleArray>(f, "DomainScatteringCoefficient", { p.DomainScatteringCoefficient });
  addArray<vtkDoubleArray>(f, "SphereRefractiveIndex", { p.SphereRefractiveIndex });
  addArray<vtkDoubleArray>(f, "MatrixRefractiveIndex", { p.MatrixRefractiveIndex });
  addArray<vtkDoubleArray>(f, "RefractiveIndex", { p.RefractiveIndex });
  addArray<vtkIntArray>(f, "MaxPlacementAttempts", { p.MaxPlacementAttempts });
  addArray<vtkIntArray>(f, "Seed", { static_cast<int>(p.Seed) });
  const opal::PresetSettings* settings = opal::presetByIndex(preset);
  vtkNew<vtkStringArray> presetName;
  presetName->SetName("Preset");
  presetName->InsertNextValue(settings ? settings->Name : "custom");
  f->AddArray(presetName);
  addArray<vtkIntArray>(f, "DomainsPlaced", { domainsPlaced });
}

void AddDomainTable(vtkDataObject* data, const opal::DomainLayout& layout)
{
  const auto count = static_cast<vtkIdType>(layout.domains().size());
  vtkNew<vtkFloatArray> normals;
  normals->SetName("DomainNormal");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> diameters;
  diameters->SetName("DomainParticleDiameter");
  diameters->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> orientations;
  orientations->SetName("DomainOrientation");
  orientations->SetNumberOfComponents(4);
  orientations->SetNumberOfTuples(count);
  for (const opal::Domain& domain : layout.domains())
  {
    normals->SetTuple(domain.Id, domain.Normal.data());
    diameters->SetValue(domain.Id, static_cast<float>(domain.ParticleDiameter));
    orientations->SetTuple(domain.Id, opal::latticeQuaternion(domain).data());
  }
  data->GetFieldData()->AddArray(normals);
  data->GetFieldData()->AddArray(diameters);
  data->GetFieldData()->AddArray(orientations);
}
} // namespace vtkOpalFieldData
