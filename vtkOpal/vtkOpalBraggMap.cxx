#include "vtkOpalBraggMap.h"

#include "OpalBraggFamilies.h"
#include "OpalBraggMap.h"
#include "OpalLatticePlanes.h"
#include "OpalMessages.h"
#include "OpalParallel.h"
#include "OpalRenderParameters.h"

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

// The crystal of the input volume as its field data records it (the model's defaults if not).
opal::ColloidalCrystal crystalOf(vtkFieldData* fields)
{
  opal::ColloidalCrystal crystal;
  for (auto [name, target] : { std::pair<const char*, double*>{ "SphereRefractiveIndex", &crystal.SphereIndex },
         std::pair<const char*, double*>{ "MatrixRefractiveIndex", &crystal.MatrixIndex } })
  {
    vtkDataArray* recorded = fields->GetArray(name);
    *target = recorded && recorded->GetNumberOfTuples() > 0 ? recorded->GetComponent(0, 0) : *target;
  }
  return crystal;
}

// What the map reads of one domain element and writes for it.
struct DomainMapping
{
  vtkDataSet* Input;
  bool OnPoints;
  vtkDataArray* Ids;
  vtkDataArray* Normals;
  vtkDataArray* Diameters;
  vtkDataArray* Orientations; // LatticeOrientation (w, x, y, z); may be absent with the (111) planes
  opal::BraggMapSettings Settings;
  bool CoupledWave;
  opal::BraggFamilySettings Families;

  void map(vtkIdType i, vtkIdList* cellPoints, BraggArrays& arrays) const
  {
    if (this->Ids->GetComponent(i, 0) < 0)
    {
      arrays.set(i, opal::BraggMapValue());
      return;
    }
    std::array<double, 3> normal;
    this->Normals->GetTuple(i, normal.data());
    const std::array<double, 3> position = positionOf(this->Input, this->OnPoints, i, cellPoints);
    const double diameter = this->Diameters->GetComponent(i, 0);
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
    std::array<double, 4> q;
    if (this->Orientations)
    {
      this->Orientations->GetTuple(i, q.data());
      return q;
    }
    // The (111) family needs only the normal: the lattice unspun about it.
    const glm::dquat unspun = opal::latticeOrientation(glm::normalize(glm::dvec3(normal[0], normal[1], normal[2])), 0.0);
    return { unspun.w, unspun.x, unspun.y, unspun.z };
  }
};
// Maps every element in chunks, with progress and abort; false if aborted or not finite.
bool mapDomains(vtkOpalBraggMap* filter, const DomainMapping& mapping, BraggArrays& arrays)
{
  const vtkIdType count = mapping.Ids->GetNumberOfTuples();
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
  const auto wavelengths = vtk::DataArrayValueRange<1>(arrays.Wavelength.GetPointer());
  if (!std::all_of(wavelengths.begin(), wavelengths.end(), [](float v) { return std::isfinite(v); }))
  {
    vtkErrorWithObjectMacro(filter, "The Bragg map produced a NaN or an infinity in BraggWavelength; check LightPosition, "
                  "EyePosition and the domain arrays.");
    return false;
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
  if (this->BraggOrder < 1 || !(this->MosaicSpread >= 0 && this->MosaicSpread <= 90))
  {
    return "BraggOrder must be at least 1 and MosaicSpread lie in [0, 90] degrees.";
  }
  if (!std::all_of(this->ModelRotation, this->ModelRotation + 3, [](double a) { return std::isfinite(a); }))
  {
    return "ModelRotation must be finite.";
  }
  if (this->BraggModel < 0 || this->BraggModel > 1 || this->LatticePlanes < 0 || this->LatticePlanes > 1)
  {
    return "BraggModel and LatticePlanes must be 0 or 1 (paper or coupled-wave; 111 or fcc).";
  }
  if (this->LatticePlanes == 1 && this->BraggModel != 1)
  {
    return "LatticePlanes fcc needs BraggModel coupled-wave (the paper's band has no families).";
  }
  if (this->CoherentLayers < 1 || this->CoherentLayers > opal::MaxCoherentLayers)
  {
    return "CoherentLayers must lie in [1, " + std::to_string(opal::MaxCoherentLayers) + "].";
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
  const bool onPoints = input->GetPointData()->GetArray("DomainId") != nullptr;
  vtkDataSetAttributes* attributes =
    onPoints ? static_cast<vtkDataSetAttributes*>(input->GetPointData()) : input->GetCellData();
  const std::string error =
    checkInput(input, attributes, onPoints, settings.LightPosition.data());
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
  const bool coupledWave = this->BraggModel == static_cast<int>(opal::BraggModelKind::CoupledWave);
  opal::BraggFamilySettings families{ static_cast<opal::LatticePlaneSet>(this->LatticePlanes), this->CoherentLayers,
    crystalOf(input->GetFieldData()) };
  settings.CoupledWaveMeanIndex = coupledWave ? opal::meanIndex(families.Crystal) : 0.0;
  vtkDataArray* orientations = attributes->GetArray("LatticeOrientation");
  if (families.LatticePlanes == opal::LatticePlaneSet::Fcc && (!orientations || orientations->GetNumberOfComponents() != 4))
  {
    vtkErrorMacro("LatticePlanes fcc needs the volume's LatticeOrientation array (4 components).");
    return 0;
  }
  const DomainMapping mapping{ input, onPoints, attributes->GetArray("DomainId"), attributes->GetArray("Normal"),
    attributes->GetArray("ParticleDiameter"), orientations, settings, coupledWave, families };
  const int familyCount = !coupledWave ? 0 : families.LatticePlanes == opal::LatticePlaneSet::Fcc ? opal::FccPlaneCount : 1;
  BraggArrays arrays(mapping.Ids->GetNumberOfTuples(), familyCount);
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
