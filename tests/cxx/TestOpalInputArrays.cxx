// The input-array rule (vtkOpal/vtkOpalInputArrays.h) for every reader:
// the render and the Bragg map with each model and lattice setting. A table
// of crafted arrays (wrong type, components, tuples; NaN, infinity; ids that
// wrap int32 or are not whole; a crystal's index the render refuses), each
// refused by every reader that reads the array, the message naming the array
// (and the true value), and the filters working again once fixed; then the
// one rule for directions: a DomainNormal, Normal or LatticeOrientation of
// any non-zero length gives what the unit one gives.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"
#include "vtkOpalBraggMap.h"
#include "vtkOpalSpectralRender.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
// The readers a crafted array must be refused by.
enum Reader : unsigned
{
  Render = 1,
  PaperMap = 2,   // the paper's Bragg model
  CoupledMap = 4, // coupled-wave, the (111) family
  FccMap = 8,     // coupled-wave, every fcc family
  EveryMap = PaperMap | CoupledMap | FccMap,
  Everyone = Render | EveryMap
};

struct CraftedCase
{
  std::string Description;
  std::function<void(vtkImageData*)> Craft;
  unsigned Readers;
  std::string Expected; // in the message
};

const double NaN = std::numeric_limits<double>::quiet_NaN();

vtkFieldData* attributesOf(vtkImageData* volume, bool field)
{
  return field ? volume->GetFieldData() : static_cast<vtkFieldData*>(volume->GetPointData());
}

// Replaces the named array by one of `components` components and `tuples`
// tuples (the original count for -1), every value `value`.
std::function<void(vtkImageData*)> reshaped(const char* name, bool field, int components, vtkIdType tuples, double value = 1)
{
  return [=](vtkImageData* volume) {
    vtkFieldData* data = attributesOf(volume, field);
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(tuples >= 0 ? tuples : data->GetArray(name)->GetNumberOfTuples());
    array->Fill(value);
    data->RemoveArray(name);
    data->AddArray(array);
  };
}

// The named array as text.
std::function<void(vtkImageData*)> asText(const char* name, bool field)
{
  return [=](vtkImageData* volume) {
    vtkFieldData* data = attributesOf(volume, field);
    vtkNew<vtkStringArray> text;
    text->SetName(name);
    text->SetNumberOfTuples(data->GetArray(name)->GetNumberOfTuples());
    data->RemoveArray(name);
    data->AddArray(text);
  };
}

// The first voxel inside a domain.
vtkIdType domainVoxel(vtkImageData* volume)
{
  vtkDataArray* ids = volume->GetPointData()->GetArray("DomainId");
  vtkIdType i = 0;
  while (ids->GetComponent(i, 0) < 0)
  {
    ++i;
  }
  return i;
}

// `value` at component 0 of a domain voxel's tuple (as a double array, so
// that any value survives), or of the field array's first.
std::function<void(vtkImageData*)> valueAt(const char* name, bool field, double value)
{
  return [=](vtkImageData* volume) {
    vtkFieldData* data = attributesOf(volume, field);
    vtkNew<vtkDoubleArray> copy;
    copy->DeepCopy(data->GetArray(name));
    copy->SetComponent(field ? 0 : domainVoxel(volume), 0, value);
    data->RemoveArray(name);
    data->AddArray(copy);
  };
}

// Every component of a domain voxel's tuple of the named point array scaled by `factor`.
std::function<void(vtkImageData*)> scaledAt(const char* name, double factor)
{
  return [=](vtkImageData* volume) {
    vtkDataArray* array = volume->GetPointData()->GetArray(name);
    const vtkIdType voxel = domainVoxel(volume);
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      array->SetComponent(voxel, c, factor * array->GetComponent(voxel, c));
    }
  };
}

std::vector<CraftedCase> craftedCases()
{
  const double inf = std::numeric_limits<double>::infinity();
  return {
    { "LatticeOrientation of 64 components", reshaped("LatticeOrientation", false, 64, -1), CoupledMap | FccMap,
      "LatticeOrientation needs 4 components, it has 64" },
    { "LatticeOrientation NaN at a domain voxel", valueAt("LatticeOrientation", false, NaN), CoupledMap | FccMap,
      "LatticeOrientation holds nan" },
    { "LatticeOrientation zero at a domain voxel", scaledAt("LatticeOrientation", 0.0), CoupledMap | FccMap,
      "LatticeOrientation at element" },
    { "Normal of 64 components", reshaped("Normal", false, 64, -1), EveryMap, "Normal needs 3 components" },
    { "Normal one tuple short", reshaped("Normal", false, 3, 5), EveryMap, "Normal needs" },
    { "Normal infinite", valueAt("Normal", false, inf), EveryMap, "Normal holds inf" },
    { "ParticleDiameter of 2 components", reshaped("ParticleDiameter", false, 2, -1), EveryMap, "ParticleDiameter" },
    { "DomainId as text", asText("DomainId", false), Everyone, "non-numeric point array DomainId" },
    { "DomainId 4294967296", valueAt("DomainId", false, 4294967296.0), Everyone, "DomainId holds 4294967296" },
    { "DomainId 1.5", valueAt("DomainId", false, 1.5), Everyone, "DomainId holds 1.5" },
    { "DomainId NaN", valueAt("DomainId", false, NaN), Everyone, "DomainId holds nan" },
    { "ScatteringCoefficient with 7 tuples", reshaped("ScatteringCoefficient", false, 1, 7), Render,
      "ScatteringCoefficient needs" },
    { "SurfaceDistance of 2 components", reshaped("SurfaceDistance", false, 2, -1), Render, "SurfaceDistance" },
    { "AbsorptionCoefficient of 3 components", reshaped("AbsorptionCoefficient", false, 3, -1), Render,
      "AbsorptionCoefficient" },
    { "DomainNormal of one component", reshaped("DomainNormal", true, 1, -1), Render, "DomainNormal needs 3" },
    { "DomainParticleDiameter short of the table", reshaped("DomainParticleDiameter", true, 1, 2), Render,
      "DomainParticleDiameter needs" },
    { "DomainOrientation of 3 components", reshaped("DomainOrientation", true, 3, -1), Render, "DomainOrientation" },
    { "DomainNormal zero", reshaped("DomainNormal", true, 3, -1, 0.0), Render, "zero DomainNormal" },
    { "SphereRefractiveIndex NaN", valueAt("SphereRefractiveIndex", true, NaN), Everyone, "SphereRefractiveIndex" },
    { "MatrixRefractiveIndex 0.5", valueAt("MatrixRefractiveIndex", true, 0.5), Everyone, "MatrixRefractiveIndex" },
    { "MatrixRefractiveIndex as text", asText("MatrixRefractiveIndex", true), Everyone, "MatrixRefractiveIndex" },
    { "RefractiveIndex NaN", valueAt("RefractiveIndex", true, NaN), Everyone, "RefractiveIndex holds nan" },
    { "RefractiveIndex without a value", reshaped("RefractiveIndex", true, 1, 0), Everyone, "RefractiveIndex needs a value" },
  };
}

// A volume with every array the readers read: the source's, and absorption.
vtkSmartPointer<vtkImageData> fullVolume()
{
  auto source = opaltest::makeSmallSource();
  source->Update();
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->DeepCopy(source->GetOutput());
  for (const char* name : { "AbsorptionCoefficient", "AbsorptionExponent" })
  {
    vtkNew<vtkFloatArray> values;
    values->SetName(name);
    values->SetNumberOfTuples(volume->GetNumberOfPoints());
    values->Fill(0.0f);
    volume->GetPointData()->AddArray(values);
  }
  return volume;
}

// A Bragg map of each reader kind.
vtkSmartPointer<vtkOpalBraggMap> mapFor(Reader reader)
{
  auto map = vtkSmartPointer<vtkOpalBraggMap>::New();
  map->SetBraggModel(reader == PaperMap ? 0 : 1);
  map->SetLatticePlanes(reader == FccMap ? 1 : 0);
  return map;
}

// Updates `filter` on `volume`; empty if it succeeded, else its first error.
std::string run(vtkAlgorithm* filter, vtkImageData* volume, bool& succeeded)
{
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(filter);
  filter->SetInputDataObject(volume);
  succeeded = filter->GetExecutive()->Update() == 1;
  return recorder->Errors.empty() ? std::string() : recorder->Errors.front();
}

// Each crafted case refused by each of its readers, naming the array; each
// reader working on the good volume after it.
void checkCraftedCases(vtkImageData* good, vtkOpalSpectralRender* render)
{
  for (const CraftedCase& crafted : craftedCases())
  {
    vtkNew<vtkImageData> volume;
    volume->DeepCopy(good);
    crafted.Craft(volume);
    for (Reader reader : { Render, PaperMap, CoupledMap, FccMap })
    {
      if (!(crafted.Readers & reader))
      {
        continue;
      }
      auto map = mapFor(reader);
      vtkAlgorithm* filter = reader == Render ? static_cast<vtkAlgorithm*>(render) : map.GetPointer();
      const std::string what = crafted.Description + " (reader " + std::to_string(reader) + ")";
      bool succeeded = true;
      const std::string error = run(filter, volume, succeeded);
      OPAL_CHECK(!succeeded, what + ": refused");
      OPAL_CHECK(error.find(crafted.Expected) != std::string::npos,
        what + ": the message says \"" + crafted.Expected + "\" (got: " + error + ")");
      OPAL_CHECK(run(filter, good, succeeded).empty() && succeeded, what + ": works again on the good volume");
    }
  }
}

// The domain polygons' cell arrays follow the same rule.
void checkPolygonCells()
{
  auto source = opaltest::makeSmallSource();
  source->Update();
  vtkNew<vtkPolyData> polygons;
  polygons->DeepCopy(source->GetOutputDataObject(1));
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normal");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(2);
  normals->Fill(1);
  polygons->GetCellData()->RemoveArray("Normal");
  polygons->GetCellData()->AddArray(normals);
  vtkNew<vtkOpalBraggMap> map;
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(map);
  map->SetInputData(polygons);
  OPAL_CHECK(map->GetExecutive()->Update() == 0, "polygons with two Normal tuples: refused");
  OPAL_CHECK(recorder->anyContains(recorder->Errors, "cell array Normal needs"), "the message names the cell array Normal");
}

// The largest difference between two filters' named float arrays.
double largestDifference(vtkDataArray* a, vtkDataArray* b)
{
  double largest = a->GetNumberOfValues() == b->GetNumberOfValues() ? 0.0 : HUGE_VAL;
  for (vtkIdType i = 0; i < a->GetNumberOfValues() && i < b->GetNumberOfValues(); ++i)
  {
    largest = std::max(largest, std::fabs(a->GetVariantValue(i).ToDouble() - b->GetVariantValue(i).ToDouble()));
  }
  return largest;
}

// Directions of any non-zero length give what the unit ones give.
void checkDirectionsNormalised(vtkImageData* good, vtkOpalSpectralRender* render)
{
  vtkNew<vtkImageData> longer;
  longer->DeepCopy(good);
  vtkDataArray* normals = longer->GetFieldData()->GetArray("DomainNormal");
  for (vtkIdType v = 0; v < normals->GetNumberOfValues(); ++v)
  {
    normals->SetVariantValue(v, 1.9 * normals->GetVariantValue(v).ToDouble());
  }
  scaledAt("Normal", 1.9)(longer);
  scaledAt("LatticeOrientation", 0.5)(longer);
  for (Reader reader : { Render, FccMap })
  {
    auto map = mapFor(reader);
    vtkAlgorithm* filter = reader == Render ? static_cast<vtkAlgorithm*>(render) : map.GetPointer();
    const char* name = reader == Render ? "Radiance" : "FamilyBraggWavelength";
    bool succeeded = false;
    run(filter, good, succeeded);
    vtkNew<vtkImageData> unit;
    unit->DeepCopy(filter->GetOutputDataObject(0));
    run(filter, longer, succeeded);
    auto* scaled = vtkImageData::SafeDownCast(filter->GetOutputDataObject(0));
    const double difference =
      largestDifference(unit->GetPointData()->GetArray(name), scaled->GetPointData()->GetArray(name));
    OPAL_CHECK(succeeded && difference < 1e-3,
      std::string(name) + " with directions of length 1.9 and 0.5 as with unit ones (largest difference " +
        std::to_string(difference) + ")");
  }
}
} // namespace

int TestOpalInputArrays(int, char*[])
{
  opaltest::silenceExpectedErrors();
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  vtkSmartPointer<vtkImageData> good = fullVolume();
  vtkNew<vtkOpalSpectralRender> render;
  render->SetImageSize(32, 24);
  checkCraftedCases(good, render);
  checkPolygonCells();
  checkDirectionsNormalised(good, render);
  return opaltest::finish("TestOpalInputArrays");
}
