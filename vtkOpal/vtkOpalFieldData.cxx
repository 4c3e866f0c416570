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
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <initializer_list>
#include <vector>

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
  for (const opal::ParameterRow<opal::ModelParameters>& row : opal::modelParameterRows())
  {
    vtkSmartPointer<vtkDataArray> array;
    if (row.Type == opal::ParameterType::Double)
    {
      array = vtkSmartPointer<vtkDoubleArray>::New();
    }
    else
    {
      array = vtkSmartPointer<vtkIntArray>::New();
    }
    array->SetName(row.Name);
    for (const double value : row.Get(p))
    {
      array->InsertNextTuple1(value); // every int row's range lies within an int's
    }
    f->AddArray(array);
  }
  const opal::PresetSettings* settings = opal::presetByIndex(preset);
  vtkNew<vtkStringArray> presetName;
  presetName->SetName("Preset");
  presetName->InsertNextValue(settings ? settings->Name : "custom");
  f->AddArray(presetName);
  addArray<vtkIntArray>(f, "DomainsPlaced", { domainsPlaced });
}

opal::ModelParameters ReadModelParameters(vtkFieldData* fields)
{
  opal::ModelParameters p;
  for (const opal::ParameterRow<opal::ModelParameters>& row : opal::modelParameterRows())
  {
    vtkDataArray* array = fields ? fields->GetArray(row.Name) : nullptr;
    if (!array || array->GetNumberOfValues() != row.Components)
    {
      continue;
    }
    std::vector<double> values(static_cast<std::size_t>(row.Components));
    for (int i = 0; i < row.Components; ++i)
    {
      values[static_cast<std::size_t>(i)] = array->GetVariantValue(i).ToDouble();
    }
    row.Set(p, values);
  }
  return p;
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
