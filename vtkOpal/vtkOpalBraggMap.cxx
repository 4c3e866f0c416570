#include "vtkOpalBraggMap.h"

#include "OpalBraggMap.h"
#include "OpalMessages.h"
#include "OpalParallel.h"

#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkOpalBraggMap);

vtkOpalBraggMap::vtkOpalBraggMap()
{
  const opal::BraggMapSettings defaults;
  std::copy(defaults.LightPosition.begin(), defaults.LightPosition.end(), this->LightPosition);
  std::copy(defaults.EyePosition.begin(), defaults.EyePosition.end(), this->EyePosition);
  std::copy(defaults.ModelRotation.begin(), defaults.ModelRotation.end(), this->ModelRotation);
  this->RefractiveIndex = 0; // the input's (its field data RefractiveIndex)
  this->BraggOrder = defaults.BraggOrder;
  this->MosaicSpread = defaults.MosaicSpread;
}

int vtkOpalBraggMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

namespace
{
// Empty if the domain arrays have their components (DomainId 1, Normal 3,
// ParticleDiameter 1) and, at every element of a domain, a finite non-zero
// Normal and a positive finite ParticleDiameter; else a sentence naming the
// array and the element.
std::string checkDomainValues(vtkDataSetAttributes* attributes)
{
  vtkDataArray* ids = attributes->GetArray("DomainId");
  vtkDataArray* normals = attributes->GetArray("Normal");
  vtkDataArray* diameters = attributes->GetArray("ParticleDiameter");
  if (ids->GetNumberOfComponents() != 1 || normals->GetNumberOfComponents() != 3 ||
    diameters->GetNumberOfComponents() != 1)
  {
    return "The arrays DomainId, Normal and ParticleDiameter need 1, 3 and 1 components.";
  }
  for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
  {
    if (!(ids->GetComponent(i, 0) >= 0))
    {
      continue;
    }
    double n[3];
    normals->GetTuple(i, n);
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double diameter = diameters->GetComponent(i, 0);
    if (!std::isfinite(length) || !(length > 0))
    {
      return "Normal at element " + std::to_string(i) + " of a domain is not a finite non-zero vector.";
    }
    if (!std::isfinite(diameter) || !(diameter > 0))
    {
      return "ParticleDiameter at element " + std::to_string(i) + " of a domain is not a positive finite size.";
    }
  }
  return {};
}

// Empty if the input carries the domain arrays (on its points for the volume,
// on its cells for the domain polygons) and the light lies outside the opal.
std::string checkInput(vtkDataSet* input, vtkDataSetAttributes* attributes, bool onPoints, const double light[3])
{
  for (const char* name : { "DomainId", "Normal", "ParticleDiameter" })
  {
    if (!attributes->GetArray(name))
    {
      return std::string("The input lacks the ") + (onPoints ? "point" : "cell") + " array " + name +
        "; connect an Opal Volume or its domain polygons.";
    }
  }
  const std::string values = checkDomainValues(attributes);
  if (!values.empty())
  {
    return values;
  }
  if (vtkImageData* image = vtkImageData::SafeDownCast(input))
  {
    vtkDataArray* distance = image->GetPointData()->GetArray("SurfaceDistance");
    const vtkIdType nearest = image->FindPoint(const_cast<double*>(light));
    if (distance && nearest >= 0 && distance->GetComponent(nearest, 0) <= 0)
    {
      std::ostringstream message;
      message << "LightPosition (" << light[0] << ", " << light[1] << ", " << light[2]
              << ") is inside the opal; place the light outside it.";
      return message.str();
    }
  }
  return {};
}

// Where element i sits: the voxel's point, or the domain polygon's centroid.
std::array<double, 3> positionOf(vtkDataSet* input, bool onPoints, vtkIdType i, vtkIdList* cellPoints)
{
  std::array<double, 3> position{ 0, 0, 0 };
  if (onPoints)
  {
    input->GetPoint(i, position.data());
    return position;
  }
  input->GetCellPoints(i, cellPoints);
  for (vtkIdType k = 0; k < cellPoints->GetNumberOfIds(); ++k)
  {
    double x[3];
    input->GetPoint(cellPoints->GetId(k), x);
    for (std::size_t a = 0; a < 3; ++a)
    {
      position[a] += x[a] / static_cast<double>(cellPoints->GetNumberOfIds());
    }
  }
  return position;
}

// The output arrays BraggWavelength, BraggVisible and BraggColor.
struct BraggArrays
{
  explicit BraggArrays(vtkIdType count)
  {
    this->Wavelength->SetName("BraggWavelength");
    this->Wavelength->SetNumberOfTuples(count);
    this->Visible->SetName("BraggVisible");
    this->Visible->SetNumberOfTuples(count);
    this->Colour->SetName("BraggColor");
    this->Colour->SetNumberOfComponents(3);
    this->Colour->SetNumberOfTuples(count);
  }
  void set(vtkIdType i, const opal::BraggMapValue& value)
  {
    this->Wavelength->SetValue(i, static_cast<float>(value.Wavelength));
    this->Visible->SetValue(i, static_cast<float>(value.Visible));
    this->Colour->SetTypedTuple(i, value.Colour.data());
  }
  vtkNew<vtkFloatArray> Wavelength, Visible;
  vtkNew<vtkUnsignedCharArray> Colour;
};
} // namespace

opal::BraggMapSettings vtkOpalBraggMap::GetSettings() const
{
  opal::BraggMapSettings settings;
  std::copy(this->LightPosition, this->LightPosition + 3, settings.LightPosition.begin());
  std::copy(this->EyePosition, this->EyePosition + 3, settings.EyePosition.begin());
  std::copy(this->ModelRotation, this->ModelRotation + 3, settings.ModelRotation.begin());
  settings.RefractiveIndex = this->RefractiveIndex;
  settings.BraggOrder = this->BraggOrder;
  settings.MosaicSpread = this->MosaicSpread;
  return settings;
}

int vtkOpalBraggMap::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* output = vtkDataSet::GetData(outputVector);
  output->ShallowCopy(input);
  if (const std::string index = opal::refractiveIndexError(this->RefractiveIndex); this->RefractiveIndex != 0 && !index.empty())
  {
    vtkErrorMacro(<< index << " (0: the volume's)");
    return 0;
  }
  if (this->BraggOrder < 1 || !(this->MosaicSpread >= 0 && this->MosaicSpread <= 90))
  {
    vtkErrorMacro("BraggOrder must be at least 1 and MosaicSpread lie in [0, 90] degrees.");
    return 0;
  }
  if (!std::all_of(this->ModelRotation, this->ModelRotation + 3, [](double a) { return std::isfinite(a); }))
  {
    vtkErrorMacro("ModelRotation must be finite.");
    return 0;
  }
  opal::BraggMapSettings settings = this->GetSettings();
  // The volume carries the domains on its points, the layout on its cells.
  const bool onPoints = input->GetPointData()->GetArray("DomainId") != nullptr;
  vtkDataSetAttributes* attributes =
    onPoints ? static_cast<vtkDataSetAttributes*>(input->GetPointData()) : input->GetCellData();
  const std::string error =
    checkInput(input, attributes, onPoints, opal::inStoneFrame(settings.LightPosition, settings).data());
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (settings.RefractiveIndex == 0)
  {
    // The volume's, as its field data records it (the volume and its domain polygons both carry it).
    vtkDataArray* recorded = input->GetFieldData()->GetArray("RefractiveIndex");
    settings.RefractiveIndex = recorded && recorded->GetNumberOfTuples() > 0 ? recorded->GetComponent(0, 0)
                                                                            : opal::BraggMapSettings().RefractiveIndex;
  }
  vtkDataArray* ids = attributes->GetArray("DomainId");
  vtkDataArray* normals = attributes->GetArray("Normal");
  vtkDataArray* diameters = attributes->GetArray("ParticleDiameter");
  const vtkIdType count = ids->GetNumberOfTuples();
  BraggArrays arrays(count);
  // Cell centres need a thread-safe GetCell: build the links once.
  if (!onPoints && count > 0)
  {
    vtkNew<vtkIdList> warmUp;
    input->GetCellPoints(0, warmUp);
  }
  const vtkIdType chunk = std::max<vtkIdType>(1, (count + 19) / 20); // 20 progress steps
  for (vtkIdType begin = 0; begin < count; begin += chunk)
  {
    if (this->GetAbortExecute())
    {
      return 0;
    }
    const vtkIdType end = std::min(count, begin + chunk);
    opal::parallelFor(static_cast<int>(begin), static_cast<int>(end), [&](int first, int last) {
      vtkNew<vtkIdList> cellPoints;
      for (vtkIdType i = first; i < last; ++i)
      {
        std::array<double, 3> normal;
        normals->GetTuple(i, normal.data());
        arrays.set(i, ids->GetComponent(i, 0) < 0 ? opal::BraggMapValue()
            : opal::braggMapAt(positionOf(input, onPoints, i, cellPoints), normal, diameters->GetComponent(i, 0), settings));
      }
    });
    this->UpdateProgress(static_cast<double>(end) / count);
  }
  const auto wavelengths = vtk::DataArrayValueRange<1>(arrays.Wavelength.GetPointer());
  if (!std::all_of(wavelengths.begin(), wavelengths.end(), [](float v) { return std::isfinite(v); }))
  {
    vtkErrorMacro("The Bragg map produced a NaN or an infinity in BraggWavelength; check LightPosition, "
                  "EyePosition and the domain arrays.");
    return 0;
  }
  vtkDataSetAttributes* out = onPoints ? static_cast<vtkDataSetAttributes*>(output->GetPointData()) : output->GetCellData();
  out->AddArray(arrays.Wavelength);
  out->AddArray(arrays.Visible);
  out->AddArray(arrays.Colour);
  // Shown first coloured by the wavelength it diffracts (ParaView colours by
  // the active scalars), in the plugin's "Visible spectrum" map.
  out->SetActiveScalars("BraggWavelength");
  return 1;
}

void vtkOpalBraggMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LightPosition: " << this->LightPosition[0] << " " << this->LightPosition[1] << " "
     << this->LightPosition[2] << "\n";
  os << indent << "EyePosition: " << this->EyePosition[0] << " " << this->EyePosition[1] << " "
     << this->EyePosition[2] << "\n";
  os << indent << "ModelRotation: " << this->ModelRotation[0] << " " << this->ModelRotation[1] << " "
     << this->ModelRotation[2] << "\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "BraggOrder: " << this->BraggOrder << "\n";
  os << indent << "MosaicSpread: " << this->MosaicSpread << "\n";
}
