#include "vtkOpalRenderInput.h"

#include "OpalDomainLayout.h"
#include "OpalMessages.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "vtkOpalInputArrays.h"
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
#include <array>
#include <cmath>

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

using Expected = vtkOpalInputArrays::Expected;

// The named point array with one finite value per point (a whole number
// within int32 for `Id`), or nullptr and the reason in `error`.
vtkDataArray* pointArray(vtkImageData* input, const char* name, bool required, std::string& error,
  Expected::Values kind = Expected::Values::Real)
{
  return vtkOpalInputArrays::Find(
    input->GetPointData(), { name, 1, input->GetNumberOfPoints(), kind }, "point array", required, error);
}

// The optional absorption (docs/design.md §2.10): AbsorptionCoefficient and
// its AbsorptionExponent (0, grey, where that array is absent); empty or the reason.
std::string readAbsorption(vtkImageData* input, opal::RenderVolume& volume, vtkOpalRenderInput::Storage& storage)
{
  std::string error;
  vtkDataArray* absorption = pointArray(input, "AbsorptionCoefficient", false, error);
  vtkDataArray* exponent = pointArray(input, "AbsorptionExponent", false, error);
  if (!error.empty() || !absorption)
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

// A domain's direction (its normal, its lattice's quaternion) made a unit
// vector: any finite non-zero one is normalised, the one rule the Bragg map
// follows too (a normal of length 1.9 once diffracted nothing); false, and
// left as it was, for zero.
template <std::size_t N>
bool normalised(std::array<double, N>& v)
{
  double squares = 0;
  for (double c : v)
  {
    squares += c * c;
  }
  const double length = std::sqrt(squares);
  if (!(length > 0))
  {
    return false;
  }
  for (double& c : v)
  {
    c /= length;
  }
  return true;
}

// The domain table from the field arrays DomainNormal, DomainParticleDiameter
// and DomainOrientation; without the last (a volume saved before it existed)
// each lattice stands unspun on its normal (docs/design.md §2.6).
std::string readDomainTable(vtkImageData* input, std::vector<opal::RenderDomain>& domains)
{
  vtkFieldData* fields = input->GetFieldData();
  std::string error;
  vtkDataArray* normals = vtkOpalInputArrays::Find(fields, { "DomainNormal", 3, Expected::AnyCount }, "field array", true, error);
  const vtkIdType count = normals ? normals->GetNumberOfTuples() : 0;
  vtkDataArray* diameters =
    vtkOpalInputArrays::Find(fields, { "DomainParticleDiameter", 1, count }, "field array", true, error);
  vtkDataArray* orientations =
    vtkOpalInputArrays::Find(fields, { "DomainOrientation", 4, count }, "field array", false, error);
  if (!error.empty())
  {
    return error + (error.find(" lacks ") != std::string::npos ? " Connect an Opal Volume." : "");
  }
  domains.resize(static_cast<std::size_t>(count));
  for (vtkIdType d = 0; d < count; ++d)
  {
    opal::Domain domain;
    normals->GetTuple(d, domain.Normal.data());
    if (!normalised(domain.Normal))
    {
      return "Domain " + std::to_string(d) + " of the domain table has a zero DomainNormal.";
    }
    std::array<double, 4> orientation = opal::latticeQuaternion(domain);
    if (orientations)
    {
      orientations->GetTuple(d, orientation.data());
    }
    if (!normalised(orientation))
    {
      return "Domain " + std::to_string(d) + " of the domain table has a zero DomainOrientation.";
    }
    domains[static_cast<std::size_t>(d)] =
      opal::renderDomain(domain.Normal, diameters->GetComponent(d, 0), orientation);
  }
  return {};
}

// The volume's indices recorded in its field data (RefractiveIndex, and the
// coupled-wave model's crystal, docs/design.md §7.2), each checked as one
// finite value; the defaults where a volume does not record them.
std::string readIndices(vtkFieldData* fields, opal::RenderVolume& volume)
{
  std::string error;
  for (auto [name, index] : { std::pair<const char*, double*>{ "SphereRefractiveIndex", &volume.SphereRefractiveIndex },
         { "MatrixRefractiveIndex", &volume.MatrixRefractiveIndex }, { "RefractiveIndex", nullptr } })
  {
    vtkDataArray* array = vtkOpalInputArrays::Find(fields, { name, 1, Expected::FieldValue }, "field array", false, error);
    if (array && index)
    {
      *index = array->GetComponent(0, 0);
    }
    else if (array && !opal::refractiveIndexError(array->GetComponent(0, 0)).empty())
    {
      error = "The field array RefractiveIndex holds " + std::to_string(array->GetComponent(0, 0)) +
        "; a volume's index lies in [1, 4).";
    }
  }
  return error;
}

// What a saved volume's field data (Preset, RefractiveIndex) implies, but
// the default image size: RequestInformation announces the extent before any
// data exists.
vtkOpalRenderInput::VolumeSettings settingsFromFieldData(vtkFieldData* fields)
{
  // A malformed index falls back to the default here; Read refuses it by name.
  double refractiveIndex = vtkOpalRenderInput::VolumeSettings().RefractiveIndex;
  vtkDataArray* index = fields->GetArray("RefractiveIndex");
  if (index && index->GetNumberOfTuples() > 0 && opal::refractiveIndexError(index->GetComponent(0, 0)).empty())
  {
    refractiveIndex = index->GetComponent(0, 0);
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
std::string Read(vtkImageData* input, opal::RenderVolume& volume, Storage& storage, const MediumPiece* medium)
{
  std::string error;
  vtkImageData* mediumArrays = medium ? medium->Arrays.Get() : input;
  vtkDataArray* scattering = pointArray(mediumArrays, "ScatteringCoefficient", true, error);
  vtkDataArray* domainIds = pointArray(mediumArrays, "DomainId", true, error, Expected::Values::Id);
  vtkDataArray* distance = pointArray(input, "SurfaceDistance", true, error);
  if (!error.empty())
  {
    return error + (error.find(" lacks ") != std::string::npos ? " Connect an Opal Volume." : "");
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
  volume.Held.reset();
  if (medium)
  {
    volume.Held = medium->Held;
  }
  for (const std::string& step :
    { readAbsorption(mediumArrays, volume, storage), readIndices(input->GetFieldData(), volume) })
  {
    if (!step.empty())
    {
      return step;
    }
  }
  return readDomainTable(input, volume.Domains);
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
