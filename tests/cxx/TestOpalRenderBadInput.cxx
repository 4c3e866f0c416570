// Bad input to the render filter: each invalid parameter fails the request
// with a message naming it; a light inside the opal, a volume without the
// opal's arrays and a device too small for the volume get clear messages; the
// filter works again once the input is fixed; input arrays with NaN, Inf,
// negative or out-of-range values fail naming the array. Run with no Vulkan driver
// (VK_ICD_FILENAMES pointing nowhere, argument "no-device") it must say
// "No Vulkan device" and fail the request.
#include "OpalRenderParameters.h"
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"
#include "OpalRenderScenes.h"
#include "vtkOpalSpectralRender.h"

#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using BadCase = opaltest::BadCase<vtkOpalSpectralRender>;

namespace
{
// A bad value in one input array: what to break and the name the message must give.
struct BadArray
{
  std::string Description;
  std::function<void(vtkImageData*)> Break;
  std::string Expected;
};

// Sets one value of a point array (the voxel near the volume's centre) or of a field array.
std::function<void(vtkImageData*)> setValue(const char* name, double value, bool field = false)
{
  return [name, value, field](vtkImageData* volume) {
    vtkDataArray* array = field ? volume->GetFieldData()->GetArray(name) : volume->GetPointData()->GetArray(name);
    array->SetComponent(field ? 0 : array->GetNumberOfTuples() / 2, 0, value);
  };
}

// Gives the volume absorption (docs/design.md §2.10: AbsorptionCoefficient
// 0.1/mm and AbsorptionExponent 2 everywhere), then `value` at the centre
// voxel of the named one of the two.
std::function<void(vtkImageData*)> absorbingWith(const char* name, double value)
{
  return [name, value](vtkImageData* volume) {
    for (const auto& [array, uniform] : { std::pair<const char*, float>{ "AbsorptionCoefficient", 0.1f },
           { "AbsorptionExponent", 2.0f } })
    {
      vtkNew<vtkFloatArray> values;
      values->SetName(array);
      values->SetNumberOfTuples(volume->GetNumberOfPoints());
      values->Fill(uniform);
      volume->GetPointData()->AddArray(values);
    }
    setValue(name, value)(volume);
  };
}

// Each bad array fails the request with a message naming it; the good volume renders again.
void checkBadArrays(vtkImageData* good, opaltest::MessageRecorder* recorder, vtkOpalSpectralRender* render)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<BadArray> cases = {
    { "NaN scattering coefficient", setValue("ScatteringCoefficient", nan), "ScatteringCoefficient" },
    { "negative scattering coefficient", setValue("ScatteringCoefficient", -1.0), "ScatteringCoefficient" },
    { "infinite surface distance", setValue("SurfaceDistance", inf), "SurfaceDistance" },
    { "NaN surface distance", setValue("SurfaceDistance", nan), "SurfaceDistance" },
    { "DomainId 1e9", setValue("DomainId", 1e9), "DomainId" },
    { "NaN domain normal", setValue("DomainNormal", nan, true), "DomainNormal" },
    { "zero domain diameter", setValue("DomainParticleDiameter", 0.0, true), "DomainParticleDiameter" },
    { "NaN domain orientation", setValue("DomainOrientation", nan, true), "DomainOrientation" },
    { "sphere index below 1", setValue("SphereRefractiveIndex", 0.5, true), "SphereRefractiveIndex" },
    { "NaN absorption", absorbingWith("AbsorptionCoefficient", nan), "AbsorptionCoefficient" },
    { "negative absorption", absorbingWith("AbsorptionCoefficient", -0.5), "AbsorptionCoefficient" },
    { "infinite absorption exponent", absorbingWith("AbsorptionExponent", inf), "AbsorptionExponent" },
    { "a second coloured exponent", absorbingWith("AbsorptionExponent", 3.0), "AbsorptionExponent" },
  };
  for (const BadArray& bad : cases)
  {
    vtkNew<vtkImageData> volume;
    volume->DeepCopy(good);
    bad.Break(volume);
    render->SetInputData(volume);
    recorder->clear();
    OPAL_CHECK(render->GetExecutive()->Update() == 0, bad.Description + ": the request fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, bad.Expected), bad.Description + ": the message names " +
        bad.Expected + (recorder->Errors.empty() ? std::string(" (no message)") : " (got: " + recorder->Errors.front() + ")"));
  }
  render->SetInputData(good);
  recorder->clear();
  OPAL_CHECK(render->GetExecutive()->Update() == 1 && recorder->Errors.empty(), "the good volume renders again");
}

// Each case breaks one parameter of a working render; the error must name it.
std::vector<BadCase> badRenderCases()
{
  return {
    { "zero image width", [](vtkOpalSpectralRender* r) { r->SetImageSize(0, 24); }, "ImageSize" },
    { "zero wavelength step", [](vtkOpalSpectralRender* r) { r->SetWavelengthStep(0); }, "WavelengthStep" },
    { "reversed wavelength range", [](vtkOpalSpectralRender* r) { r->SetWavelengthRange(780, 380); },
      "WavelengthRange" },
    { "refractive index below 1", [](vtkOpalSpectralRender* r) { r->SetRefractiveIndex(0.5); }, "RefractiveIndex" },
    { "bandwidth 2", [](vtkOpalSpectralRender* r) { r->SetBraggBandwidth(2.0); }, "BraggBandwidth" },
    { "no coherent layers", [](vtkOpalSpectralRender* r) { r->SetCoherentLayers(0); }, "CoherentLayers" },
    { "fcc planes with the paper's model", [](vtkOpalSpectralRender* r) { r->SetLatticePlanes(1); }, "LatticePlanes" },
    { "view angle 0", [](vtkOpalSpectralRender* r) { r->SetViewAngle(0); }, "ViewAngle" },
    { "negative step size", [](vtkOpalSpectralRender* r) { r->SetStepSize(-1); }, "StepSize" },
    { "infinite light radius", [](vtkOpalSpectralRender* r) { r->SetLightRadius(HUGE_VAL); }, "LightRadius" },
    { "diffraction gain 1e300", [](vtkOpalSpectralRender* r) { r->SetDiffractionGain(1e300); }, "DiffractionGain" },
    { "wavelength step 1e308", [](vtkOpalSpectralRender* r) { r->SetWavelengthStep(1e308); }, "WavelengthStep" },
    { "infinite wavelength step", [](vtkOpalSpectralRender* r) { r->SetWavelengthStep(HUGE_VAL); }, "WavelengthStep" },
    { "wavelength step 1e-7", [](vtkOpalSpectralRender* r) { r->SetWavelengthStep(1e-7); }, "WavelengthStep" },
    { "NaN light position", [](vtkOpalSpectralRender* r) { r->SetLightPosition(NAN, 60, 0); }, "LightPosition" },
    { "region outside the image", [](vtkOpalSpectralRender* r) { r->SetImageRegion(40, 0, 8, 8); }, "ImageRegion" },
    { "light inside the opal", [](vtkOpalSpectralRender* r) { r->SetLightPosition(0, 2, 0); }, "LightPosition" },
    { "eye inside the opal", [](vtkOpalSpectralRender* r) { r->SetEyePosition(0, 2, 0); }, "EyePosition" },
    { "device too small for volume and image",
      [](vtkOpalSpectralRender* r) {
        r->SetDeviceMemoryLimit(1);
        r->SetImageSize(640, 480);
      },
      "device memory limit" },
  };
}

// Each bad case fails the request naming its parameter; fixed, the filter renders again.
void checkBadParameters(vtkOpalSpectralRender* render, opaltest::MessageRecorder* recorder)
{
  for (const BadCase& bad : badRenderCases())
  {
    vtkNew<vtkOpalSpectralRender> fresh;
    render->SetRenderParameters(fresh->GetRenderParameters());
    render->SetImageSize(32, 24);
    render->SetDeviceMemoryLimit(0);
    bad.Break(render);
    recorder->clear();
    OPAL_CHECK(render->GetExecutive()->Update() == 0, bad.Description + ": the request fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, bad.Expected),
      bad.Description + ": the message names " + bad.Expected +
        (recorder->Errors.empty() ? std::string(" (no message)") : " (got: " + recorder->Errors.front() + ")"));
  }
  vtkNew<vtkOpalSpectralRender> fresh;
  render->SetRenderParameters(fresh->GetRenderParameters());
  render->SetImageSize(32, 24);
  render->SetDeviceMemoryLimit(0);
  recorder->clear();
  OPAL_CHECK(render->GetExecutive()->Update() == 1 && recorder->Errors.empty(),
    "the filter recovers once fixed" + (recorder->Errors.empty() ? std::string() : ": " + recorder->Errors.front()));
}

} // namespace

int TestOpalRenderBadInput(int argc, char* argv[])
{
  opaltest::silenceExpectedErrors();
  auto source = opaltest::makeSmallSource();
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(32, 24);
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(render);

  if (argc > 1 && std::string(argv[1]) == "no-device")
  {
    OPAL_CHECK(render->GetExecutive()->Update() == 0, "without a Vulkan driver the request fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, "No Vulkan device"), "the error says: No Vulkan device");
    return opaltest::finish("TestOpalRenderNoDevice");
  }
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }

  checkBadParameters(render, recorder);
  opaltest::checkRefusesNonOpalVolume<vtkOpalSpectralRender>("ScatteringCoefficient");
  source->Update();
  vtkNew<vtkImageData> good;
  good->DeepCopy(source->GetOutput());
  checkBadArrays(good, recorder, render);
  return opaltest::finish("TestOpalRenderBadInput");
}
