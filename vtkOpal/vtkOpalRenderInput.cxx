#include "vtkOpalRenderInput.h"

#include "OpalDomainLayout.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "vtkOpalSource.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArrayRange.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <algorithm>

namespace
{
// A one-component point array as contiguous values of type T: its own memory
// when it already is an AOS array of T, else a converted copy in `storage`.
template <typename T>
const T* contiguousValues(vtkDataArray* array, std::vector<T>& storage)
{
  if (auto* typed = vtkAOSDataArrayTemplate<T>::FastDownCast(array))
  {
    return typed->GetPointer(0);
  }
  storage.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
  auto convert = [&storage](auto* source) {
    const auto values = vtk::DataArrayValueRange<1>(source);
    std::transform(values.begin(), values.end(), storage.begin(), [](auto v) { return static_cast<T>(v); });
  };
  if (!vtkArrayDispatch::Dispatch::Execute(array, convert))
  {
    convert(array);
  }
  return storage.data();
}

// The named point array with one value per point, or nullptr and a reason.
vtkDataArray* scalarArray(vtkImageData* input, const char* name, std::string& error)
{
  vtkDataArray* array = input->GetPointData()->GetArray(name);
  if (!array)
  {
    error = std::string("The input lacks the point array ") + name + "; connect an Opal Volume.";
  }
  else if (array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    error = std::string("The point array ") + name + " needs one component per point.";
    array = nullptr;
  }
  return array;
}

// The optional absorption (docs/design.md §2.10): AbsorptionCoefficient and
// its AbsorptionExponent (0, grey, where that array is absent); empty or the reason.
std::string readAbsorption(vtkImageData* input, opal::RenderVolume& volume, vtkOpalRenderInput::Storage& storage)
{
  vtkPointData* points = input->GetPointData();
  if (!points->GetArray("AbsorptionCoefficient"))
  {
    return {};
  }
  std::string error;
  vtkDataArray* absorption = scalarArray(input, "AbsorptionCoefficient", error);
  vtkDataArray* exponent = points->GetArray("AbsorptionExponent") ? scalarArray(input, "AbsorptionExponent", error) : nullptr;
  if (!error.empty())
  {
    return error;
  }
  volume.AbsorptionCoefficient = contiguousValues(absorption, storage.Absorption);
  if (exponent)
  {
    volume.AbsorptionExponent = contiguousValues(exponent, storage.AbsorptionExponent);
  }
  else
  {
    storage.AbsorptionExponent.assign(static_cast<std::size_t>(input->GetNumberOfPoints()), 0.0f);
    volume.AbsorptionExponent = storage.AbsorptionExponent.data();
  }
  return {};
}

// The domain table from the field arrays DomainNormal, DomainParticleDiameter
// and DomainOrientation; without the last (a volume saved before it existed)
// each lattice stands unspun on its normal (docs/design.md §2.6).
std::string readDomainTable(vtkImageData* input, std::vector<opal::RenderDomain>& domains)
{
  vtkFieldData* fields = input->GetFieldData();
  vtkDataArray* normals = fields->GetArray("DomainNormal");
  vtkDataArray* diameters = fields->GetArray("DomainParticleDiameter");
  vtkDataArray* orientations = fields->GetArray("DomainOrientation");
  if (!normals || !diameters || normals->GetNumberOfComponents() != 3 ||
    normals->GetNumberOfTuples() != diameters->GetNumberOfTuples())
  {
    return "The input lacks the domain table (field arrays DomainNormal and DomainParticleDiameter); "
           "connect an Opal Volume.";
  }
  if (orientations &&
    (orientations->GetNumberOfComponents() != 4 || orientations->GetNumberOfTuples() != normals->GetNumberOfTuples()))
  {
    return "The field array DomainOrientation needs 4 components (w, x, y, z) per domain.";
  }
  domains.resize(static_cast<std::size_t>(normals->GetNumberOfTuples()));
  for (vtkIdType d = 0; d < normals->GetNumberOfTuples(); ++d)
  {
    opal::Domain domain;
    normals->GetTuple(d, domain.Normal.data());
    std::array<double, 4> orientation = opal::latticeQuaternion(domain);
    if (orientations)
    {
      orientations->GetTuple(d, orientation.data());
    }
    domains[static_cast<std::size_t>(d)] =
      opal::renderDomain(domain.Normal, diameters->GetComponent(d, 0), orientation);
  }
  return {};
}

// The coupled-wave model's crystal from the field data (docs/design.md §7.2);
// the defaults where a volume does not record it.
void readCrystal(vtkFieldData* fields, opal::RenderVolume& volume)
{
  for (auto [name, index] : { std::pair<const char*, double*>{ "SphereRefractiveIndex", &volume.SphereRefractiveIndex },
         { "MatrixRefractiveIndex", &volume.MatrixRefractiveIndex } })
  {
    vtkDataArray* array = fields->GetArray(name);
    if (array && array->GetNumberOfTuples() > 0)
    {
      *index = array->GetComponent(0, 0);
    }
  }
}

// What a saved volume's field data (Preset, RefractiveIndex) implies, but
// the default image size: RequestInformation announces the extent before any
// data exists.
vtkOpalRenderInput::VolumeSettings settingsFromFieldData(vtkFieldData* fields)
{
  double refractiveIndex = vtkOpalRenderInput::VolumeSettings().RefractiveIndex;
  if (vtkDataArray* index = fields->GetArray("RefractiveIndex"))
  {
    refractiveIndex = index->GetNumberOfTuples() > 0 ? index->GetComponent(0, 0) : refractiveIndex;
  }
  int preset = opal::CustomPreset;
  auto* name = vtkStringArray::SafeDownCast(fields->GetAbstractArray("Preset"));
  if (name && name->GetNumberOfValues() > 0)
  {
    preset = opal::presetIndexByName(name->GetValue(0));
  }
  vtkOpalRenderInput::VolumeSettings settings = opal::renderHints(preset, refractiveIndex);
  settings.ImageSize = vtkOpalRenderInput::VolumeSettings().ImageSize;
  return settings;
}
} // namespace

namespace vtkOpalRenderInput
{
std::string Read(vtkImageData* input, opal::RenderVolume& volume, Storage& storage)
{
  std::string error;
  vtkDataArray* scattering = scalarArray(input, "ScatteringCoefficient", error);
  vtkDataArray* domainIds = scattering ? scalarArray(input, "DomainId", error) : nullptr;
  vtkDataArray* distance = domainIds ? scalarArray(input, "SurfaceDistance", error) : nullptr;
  if (!distance)
  {
    return error;
  }
  int dims[3], extent[6];
  double origin[3], spacing[3];
  input->GetDimensions(dims);
  input->GetExtent(extent);
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  for (std::size_t a = 0; a < 3; ++a)
  {
    volume.Dimensions[a] = dims[a];
    volume.Origin[a] = origin[a] + extent[2 * a] * spacing[a];
    volume.Spacing[a] = spacing[a];
  }
  volume.ScatteringCoefficient = contiguousValues(scattering, storage.Scattering);
  volume.DomainId = contiguousValues(domainIds, storage.DomainId);
  volume.SurfaceDistance = contiguousValues(distance, storage.SurfaceDistance);
  error = readAbsorption(input, volume, storage);
  readCrystal(input->GetFieldData(), volume);
  return error.empty() ? readDomainTable(input, volume.Domains) : error;
}

VolumeSettings ReadSettings(vtkInformation* inputInformation, vtkImageData* volume)
{
  vtkInformationDoubleVectorKey* key = vtkOpalSource::RENDER_HINTS();
  if (inputInformation && inputInformation->Has(key) && inputInformation->Length(key) == opal::RenderHintsSize)
  {
    return opal::unpackHints(inputInformation->Get(key));
  }
  return volume ? settingsFromFieldData(volume->GetFieldData()) : VolumeSettings();
}
} // namespace vtkOpalRenderInput
