#include "vtkOpalBraggMap.h"

#include "OpalBraggFamilies.h"
#include "OpalBraggMap.h"
#include "OpalLatticePlanes.h"
#include "OpalMessages.h"
#include "OpalParallel.h"
#include "OpalRenderParameters.h"
#include "vtkOpalInputArrays.h"

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
#include <utility>
#include <vector>

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
  const opal::RenderParameters render; // one set of defaults with the render's (§7.2)
  this->BraggModel = static_cast<int>(render.BraggModel);
  this->LatticePlanes = static_cast<int>(render.LatticePlanes);
  this->CoherentLayers = render.CoherentLayers;
}

int vtkOpalBraggMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

namespace
{
using Expected = vtkOpalInputArrays::Expected;

// The arrays the map reads of each element, checked by the input-array rule
// (vtkOpalInputArrays): DomainId, Normal and ParticleDiameter, and with the
// coupled-wave model the LatticeOrientation (required for fcc; without it
// the (111) family stands unspun on the normal).
struct DomainArrays
{
  vtkDataArray *Ids = nullptr, *Normals = nullptr, *Diameters = nullptr, *Orientations = nullptr;
};

// The domain arrays of `attributes` (one tuple per element), the
// LatticeOrientation with the coupled-wave model's settings only; an empty
// string, or the sentence naming the array.
std::string findDomainArrays(vtkDataSetAttributes* attributes, vtkIdType elements, bool onPoints,
  const opal::BraggFamilySettings* coupledWave, DomainArrays& arrays)
{
  const char* role = onPoints ? "point array" : "cell array";
  std::string error;
  arrays.Ids = vtkOpalInputArrays::Find(attributes, { "DomainId", 1, elements, Expected::Values::Id }, role, true, error);
  arrays.Normals = vtkOpalInputArrays::Find(attributes, { "Normal", 3, elements }, role, true, error);
  arrays.Diameters = vtkOpalInputArrays::Find(attributes, { "ParticleDiameter", 1, elements }, role, true, error);
  if (!error.empty())
  {
    return error + (error.find(" lacks ") != std::string::npos ? " Connect an Opal Volume or its domain polygons." : "");
  }
  if (!coupledWave)
  {
    return {};
  }
  if (coupledWave->LatticePlanes == opal::LatticePlaneSet::Fcc &&
    !attributes->GetAbstractArray("LatticeOrientation"))
  {
    return std::string("LatticePlanes fcc needs the volume's ") + role + " LatticeOrientation (4 components).";
  }
  arrays.Orientations = vtkOpalInputArrays::Find(attributes, { "LatticeOrientation", 4, elements }, role, false, error);
  return error;
}

// The Euclidean length of tuple i of `array`.
double tupleLength(vtkDataArray* array, vtkIdType i)
{
  double squares = 0;
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
  {
    squares += array->GetComponent(i, c) * array->GetComponent(i, c);
  }
  return std::sqrt(squares);
}

// Empty if every element of a domain has a non-zero Normal (and
// LatticeOrientation, where read) and a positive ParticleDiameter: the map
// normalises the directions, as the render does its domain table; else the
// sentence naming the array and the element.
std::string checkDomainValues(const DomainArrays& arrays)
{
  for (vtkIdType i = 0; i < arrays.Ids->GetNumberOfTuples(); ++i)
  {
    if (arrays.Ids->GetComponent(i, 0) < 0)
    {
      continue;
    }
    if (!(tupleLength(arrays.Normals, i) > 0))
    {
      return "Normal at element " + std::to_string(i) + " of a domain is not a finite non-zero vector.";
    }
    if (!(arrays.Diameters->GetComponent(i, 0) > 0))
    {
      return "ParticleDiameter at element " + std::to_string(i) + " of a domain is not a positive finite size.";
    }
    if (arrays.Orientations && !(tupleLength(arrays.Orientations, i) > 0))
    {
      return "LatticeOrientation at element " + std::to_string(i) + " of a domain is not a non-zero quaternion.";
    }
  }
  return {};
}

// Empty if the light lies outside the opal (a volume's SurfaceDistance says).
std::string checkLight(vtkDataSet* input, const double light[3])
{
  vtkImageData* image = vtkImageData::SafeDownCast(input);
  vtkDataArray* distance = image ? image->GetPointData()->GetArray("SurfaceDistance") : nullptr;
  const vtkIdType nearest = distance ? image->FindPoint(const_cast<double*>(light)) : -1;
  if (nearest >= 0 && nearest < distance->GetNumberOfTuples() && distance->GetComponent(nearest, 0) <= 0)
  {
    std::ostringstream message;
    message << "LightPosition (" << light[0] << ", " << light[1] << ", " << light[2]
            << ") is inside the opal; place the light outside it.";
    return message.str();
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

// The output arrays BraggWavelength, BraggVisible and BraggColor; with the
// coupled-wave model BraggPeakReflectance, and with fcc planes the families'
// FamilyBraggWavelength and FamilyPeakReflectance (docs/design.md §7.3).
struct BraggArrays
{
  BraggArrays(vtkIdType count, int families)
    : Families(families)
  {
    this->Colour->SetNumberOfComponents(3);
    this->FamilyWavelength->SetNumberOfComponents(std::max(families, 1));
    this->FamilyPeak->SetNumberOfComponents(std::max(families, 1));
    const std::pair<vtkDataArray*, const char*> named[] = { { this->Wavelength, "BraggWavelength" },
      { this->Visible, "BraggVisible" }, { this->Colour, "BraggColor" }, { this->Peak, "BraggPeakReflectance" },
      { this->FamilyWavelength, "FamilyBraggWavelength" }, { this->FamilyPeak, "FamilyPeakReflectance" } };
    for (const auto& [array, name] : named)
    {
      array->SetName(name);
      array->SetNumberOfTuples(count);
    }
    this->FamilyWavelength->Fill(0);
    this->FamilyPeak->Fill(0);
    this->Peak->Fill(0);
  }
  void set(vtkIdType i, const opal::BraggMapValue& value)
  {
    this->Wavelength->SetValue(i, static_cast<float>(value.Wavelength));
    this->Visible->SetValue(i, static_cast<float>(value.Visible));
    this->Colour->SetTypedTuple(i, value.Colour.data());
  }
  void setFamilies(vtkIdType i, const std::vector<opal::BraggFamilyValue>& families)
  {
    this->Peak->SetValue(i, static_cast<float>(families.at(0).PeakReflectance));
    for (int f = 0; f < static_cast<int>(families.size()) && this->Families > 1; ++f)
    {
      this->FamilyWavelength->SetComponent(i, f, families[static_cast<std::size_t>(f)].Wavelength);
      this->FamilyPeak->SetComponent(i, f, families[static_cast<std::size_t>(f)].PeakReflectance);
    }
  }
  void addTo(vtkDataSetAttributes* out) const
  {
    out->AddArray(this->Wavelength);
    out->AddArray(this->Visible);
    out->AddArray(this->Colour);
    if (this->Families > 0)
    {
      out->AddArray(this->Peak);
    }
    if (this->Families > 1)
    {
      out->AddArray(this->FamilyWavelength);
      out->AddArray(this->FamilyPeak);
    }
  }
  int Families; // 0: the paper's model; 1: the (111) family; 13: fcc
  vtkNew<vtkFloatArray> Wavelength, Visible, Peak, FamilyWavelength, FamilyPeak;
  vtkNew<vtkUnsignedCharArray> Colour;
};

// The volume's index (RefractiveIndex, for a filter's 0) and crystal
// (SphereRefractiveIndex, MatrixRefractiveIndex) as its field data records
// them, checked by the render's rules; the defaults where absent. An empty
// string, or the sentence naming the field array.
std::string readIndices(vtkFieldData* fields, double& refractiveIndex, opal::ColloidalCrystal& crystal)
{
  std::string error;
  for (auto [name, target] : { std::pair<const char*, double*>{ "RefractiveIndex", &refractiveIndex },
         { "SphereRefractiveIndex", &crystal.SphereIndex }, { "MatrixRefractiveIndex", &crystal.MatrixIndex } })
  {
    vtkDataArray* recorded = vtkOpalInputArrays::Find(fields, { name, 1, Expected::FieldValue }, "field array", false, error);
    *target = recorded ? recorded->GetComponent(0, 0) : *target;
  }
  if (error.empty() && !opal::refractiveIndexError(refractiveIndex).empty())
  {
    error = "The field array RefractiveIndex holds " + std::to_string(refractiveIndex) + "; a volume's index lies in [1, 4).";
  }
  return error.empty() ? opal::crystalError(crystal) : error;
}

// What the map reads of one domain element and writes for it.
struct DomainMapping
{
  vtkDataSet* Input;
  bool OnPoints;
  DomainArrays Arrays;
  opal::BraggMapSettings Settings;
  bool CoupledWave;
  opal::BraggFamilySettings Families;

  void map(vtkIdType i, vtkIdList* cellPoints, BraggArrays& arrays) const
  {
    if (this->Arrays.Ids->GetComponent(i, 0) < 0)
    {
      arrays.set(i, opal::BraggMapValue());
      return;
    }
    std::array<double, 3> normal;
    this->Arrays.Normals->GetTuple(i, normal.data());
    const std::array<double, 3> position = positionOf(this->Input, this->OnPoints, i, cellPoints);
    const double diameter = this->Arrays.Diameters->GetComponent(i, 0);
    arrays.set(i, opal::braggMapAt(position, normal, diameter, this->Settings));
    if (this->CoupledWave)
    {
      const std::array<double, 3>& light = this->Settings.LightPosition; // in the stone's frame
      const glm::dvec3 toward = glm::normalize(glm::dvec3(light[0], light[1], light[2]) -
        glm::dvec3(position[0], position[1], position[2]));
      arrays.setFamilies(i, opal::braggFamiliesAt(this->orientationAt(i, normal), diameter,
        { toward.x, toward.y, toward.z }, this->Families));
    }
  }

  std::array<double, 4> orientationAt(vtkIdType i, const std::array<double, 3>& normal) const
  {
    if (this->Arrays.Orientations)
    {
      glm::dquat q;
      double wxyz[4];
      this->Arrays.Orientations->GetTuple(i, wxyz);
      q = glm::normalize(glm::dquat(wxyz[0], wxyz[1], wxyz[2], wxyz[3])); // non-zero: checkDomainValues
      return { q.w, q.x, q.y, q.z };
    }
    // The (111) family needs only the normal: the lattice unspun about it.
    const glm::dquat unspun = opal::latticeOrientation(glm::normalize(glm::dvec3(normal[0], normal[1], normal[2])), 0.0);
    return { unspun.w, unspun.x, unspun.y, unspun.z };
  }
};
// Maps every element in chunks, with progress and abort; false if aborted or not finite.
bool mapDomains(vtkOpalBraggMap* filter, const DomainMapping& mapping, BraggArrays& arrays)
{
  const vtkIdType count = mapping.Arrays.Ids->GetNumberOfTuples();
  // Cell centres need a thread-safe GetCell: build the links once.
  if (!mapping.OnPoints && count > 0)
  {
    vtkNew<vtkIdList> warmUp;
    mapping.Input->GetCellPoints(0, warmUp);
  }
  const vtkIdType chunk = std::max<vtkIdType>(1, (count + 19) / 20); // 20 progress steps
  for (vtkIdType begin = 0; begin < count; begin += chunk)
  {
    if (filter->GetAbortExecute())
    {
      return false;
    }
    const vtkIdType end = std::min(count, begin + chunk);
    opal::parallelFor(static_cast<int>(begin), static_cast<int>(end), [&](int first, int last) {
      vtkNew<vtkIdList> cellPoints;
      for (vtkIdType i = first; i < last; ++i)
      {
        mapping.map(i, cellPoints, arrays);
      }
    });
    filter->UpdateProgress(static_cast<double>(end) / count);
  }
  for (vtkFloatArray* output : { arrays.Wavelength.GetPointer(), arrays.Visible.GetPointer(), arrays.Peak.GetPointer(),
         arrays.FamilyWavelength.GetPointer(), arrays.FamilyPeak.GetPointer() })
  {
    const auto values = vtk::DataArrayValueRange(output);
    if (!std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); }))
    {
      vtkErrorWithObjectMacro(filter, "The Bragg map produced a NaN or an infinity in "
          << output->GetName() << "; check LightPosition, EyePosition and the domain arrays.");
      return false;
    }
  }
  return true;
}

} // namespace

std::string vtkOpalBraggMap::SettingsError() const
{
  if (const std::string index = opal::refractiveIndexError(this->RefractiveIndex); this->RefractiveIndex != 0 && !index.empty())
  {
    return index + " (0: the volume's)";
  }
  if (this->BraggOrder < 1)
  {
    return "BraggOrder must be at least 1, got " + std::to_string(this->BraggOrder) + ".";
  }
  if (!(this->MosaicSpread >= 0 && this->MosaicSpread <= 90))
  {
    return "MosaicSpread must lie in [0, 90] degrees, got " + std::to_string(this->MosaicSpread) + ".";
  }
  if (!std::all_of(this->ModelRotation, this->ModelRotation + 3, [](double a) { return std::isfinite(a); }))
  {
    return "ModelRotation must be finite.";
  }
  // The coupled-wave settings by the render table's rows: one rule, and one
  // message, for both filters.
  opal::RenderParameters coupled;
  coupled.BraggModel = static_cast<opal::BraggModelKind>(this->BraggModel);
  coupled.LatticePlanes = static_cast<opal::LatticePlaneSet>(this->LatticePlanes);
  coupled.CoherentLayers = this->CoherentLayers;
  for (const char* name : { "BraggModel", "LatticePlanes", "CoherentLayers" })
  {
    const auto* row = opal::findRow(opal::renderParameterRows(), name);
    if (std::string error = opal::rowRangeError(row->Name, row->Get(coupled), row->Min, row->Max, row->Choices);
        !error.empty())
    {
      return error;
    }
  }
  if (coupled.LatticePlanes == opal::LatticePlaneSet::Fcc && coupled.BraggModel != opal::BraggModelKind::CoupledWave)
  {
    return "LatticePlanes fcc needs BraggModel coupled-wave (the paper's band has no families).";
  }
  return {};
}

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
  if (const std::string error = this->SettingsError(); !error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  opal::BraggMapSettings settings = opal::inStoneFrame(this->GetSettings()); // light and eye turned once
  // The volume carries the domains on its points, the layout on its cells.
  const bool onPoints = input->GetPointData()->GetAbstractArray("DomainId") != nullptr;
  vtkDataSetAttributes* attributes =
    onPoints ? static_cast<vtkDataSetAttributes*>(input->GetPointData()) : input->GetCellData();
  DomainArrays domainArrays;
  const bool coupledWave = this->BraggModel == static_cast<int>(opal::BraggModelKind::CoupledWave);
  opal::BraggFamilySettings families{ static_cast<opal::LatticePlaneSet>(this->LatticePlanes), this->CoherentLayers, {} };
  double volumeIndex = opal::BraggMapSettings().RefractiveIndex;
  std::string error = findDomainArrays(
    attributes, onPoints ? input->GetNumberOfPoints() : input->GetNumberOfCells(), onPoints, coupledWave ? &families : nullptr,
    domainArrays);
  error = error.empty() ? checkDomainValues(domainArrays) : error;
  error = error.empty() ? readIndices(input->GetFieldData(), volumeIndex, families.Crystal) : error;
  error = error.empty() ? checkLight(input, settings.LightPosition.data()) : error;
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  settings.RefractiveIndex = settings.RefractiveIndex == 0 ? volumeIndex : settings.RefractiveIndex;
  settings.CoupledWaveMeanIndex = coupledWave ? opal::meanIndex(families.Crystal) : 0.0;
  const DomainMapping mapping{ input, onPoints, domainArrays, settings, coupledWave, families };
  const int familyCount = !coupledWave ? 0 : families.LatticePlanes == opal::LatticePlaneSet::Fcc ? opal::FccPlaneCount : 1;
  BraggArrays arrays(domainArrays.Ids->GetNumberOfTuples(), familyCount);
  if (!mapDomains(this, mapping, arrays))
  {
    return 0;
  }
  vtkDataSetAttributes* out = onPoints ? static_cast<vtkDataSetAttributes*>(output->GetPointData()) : output->GetCellData();
  arrays.addTo(out);
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
  os << indent << "BraggModel: " << this->BraggModel << "\n";
  os << indent << "LatticePlanes: " << this->LatticePlanes << "\n";
  os << indent << "CoherentLayers: " << this->CoherentLayers << "\n";
}
