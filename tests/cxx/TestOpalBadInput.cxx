// Each invalid parameter fails the pipeline request with a message naming the
// parameter, and the source works again once the parameter is fixed.
// Domains that cannot all be placed give a warning and the placed count.
#include "OpalModelParameters.h"
#include "OpalTestVolumes.h"

#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using BadCase = opaltest::BadCase<vtkOpalSource>;
using opaltest::MessageRecorder;

namespace
{
// Each case breaks one parameter of a working source; the error must name it.
std::vector<BadCase> badSourceCases()
{
  return {
    { "zero dimension", [](vtkOpalSource* s) { s->SetDimensions(40, 0, 50); }, "Dimensions" },
    { "negative dimension", [](vtkOpalSource* s) { s->SetDimensions(-4, 20, 50); }, "Dimensions" },
    { "zero size", [](vtkOpalSource* s) { s->SetPhysicalSize(16, 0, 20); }, "PhysicalSize" },
    { "negative size", [](vtkOpalSource* s) { s->SetPhysicalSize(-16, 8, 20); }, "PhysicalSize" },
    { "negative semi-axis", [](vtkOpalSource* s) { s->SetSemiAxes(8, -8, 10); }, "SemiAxes" },
    { "shape wider than the box", [](vtkOpalSource* s) { s->SetSemiAxes(9, 8, 10); }, "does not fit" },
    { "shape taller than the box", [](vtkOpalSource* s) { s->SetSemiAxes(8, 8.5, 10); }, "SemiAxes" },
    { "scattering diameters min > max",
      [](vtkOpalSource* s) { s->SetScatteringDiameterRange(50, 5); }, "ScatteringDiameterRange" },
    { "domain diameters min > max",
      [](vtkOpalSource* s) {
        s->SetPreset(0);
        s->SetDomainDiameterRange(300, 200);
      },
      "DomainDiameterRange" },
    { "domain radii min > max", [](vtkOpalSource* s) { s->SetDomainRadiusRange(2, 1); }, "DomainRadiusRange" },
    { "two vertices", [](vtkOpalSource* s) { s->SetDomainVertexRange(2, 6); }, "DomainVertexRange" },
    { "vertex range min > max", [](vtkOpalSource* s) { s->SetDomainVertexRange(8, 5); }, "DomainVertexRange" },
    { "volume fraction 0", [](vtkOpalSource* s) { s->SetScatteringVolumeFraction(0); }, "ScatteringVolumeFraction" },
    { "volume fraction 0.8", [](vtkOpalSource* s) { s->SetScatteringVolumeFraction(0.8); },
      "ScatteringVolumeFraction" },
    { "negative volume fraction", [](vtkOpalSource* s) { s->SetScatteringVolumeFraction(-0.1); },
      "ScatteringVolumeFraction" },
    { "angle range min > max", [](vtkOpalSource* s) { s->SetDomainAngleRange(170, 30); }, "DomainAngleRange" },
    { "tilt beyond 90 deg", [](vtkOpalSource* s) { s->SetDomainRotationRange(0, 120); }, "DomainRotationRange" },
    { "vertex jitter 0", [](vtkOpalSource* s) { s->SetDomainVertexJitter(0, 1); }, "DomainVertexJitter" },
    { "negative domain count", [](vtkOpalSource* s) { s->SetDomainCount(-1); }, "DomainCount" },
    { "refractive index below 1", [](vtkOpalSource* s) { s->SetRefractiveIndex(0.9); }, "RefractiveIndex" },
    { "no placement attempts", [](vtkOpalSource* s) { s->SetMaxPlacementAttempts(0); }, "MaxPlacementAttempts" },
    { "unknown preset", [](vtkOpalSource* s) { s->SetPreset(99); }, "Preset" },
    { "unknown layout", [](vtkOpalSource* s) { s->SetDomainLayout(2); }, "DomainLayout" },
    { "no Voronoi cells", [](vtkOpalSource* s) { s->SetVoronoiCellCount(0); }, "VoronoiCellCount" },
    { "too many Voronoi cells", [](vtkOpalSource* s) { s->SetVoronoiCellCount(2000000); }, "VoronoiCellCount" },
    { "negative weight spread", [](vtkOpalSource* s) { s->SetVoronoiWeightSpread(-0.1); }, "VoronoiWeightSpread" },
    { "NaN weight spread", [](vtkOpalSource* s) { s->SetVoronoiWeightSpread(std::nan("")); }, "VoronoiWeightSpread" },
    { "ordered fraction above 1", [](vtkOpalSource* s) { s->SetOrderedFraction(1.5); }, "OrderedFraction" },
    { "negative ordered fraction", [](vtkOpalSource* s) { s->SetOrderedFraction(-0.5); }, "OrderedFraction" },
    { "negative correlation length", [](vtkOpalSource* s) { s->SetDiameterCorrelationLength(-1); },
      "DiameterCorrelationLength" },
    { "infinite correlation length",
      [](vtkOpalSource* s) { s->SetDiameterCorrelationLength(std::numeric_limits<double>::infinity()); },
      "DiameterCorrelationLength" },
    { "negative body absorption", [](vtkOpalSource* s) { s->SetBodyAbsorption(-0.1); }, "BodyAbsorption" },
    { "NaN body absorption", [](vtkOpalSource* s) { s->SetBodyAbsorption(std::nan("")); }, "BodyAbsorption" },
    { "absorption exponent 20", [](vtkOpalSource* s) { s->SetBodyAbsorptionExponent(20); },
      "BodyAbsorptionExponent" },
    { "infinite absorption exponent",
      [](vtkOpalSource* s) { s->SetBodyAbsorptionExponent(-std::numeric_limits<double>::infinity()); },
      "BodyAbsorptionExponent" },
    { "negative backing thickness", [](vtkOpalSource* s) { s->SetBackingThickness(-1); }, "BackingThickness" },
    { "backing thicker than the box", [](vtkOpalSource* s) { s->SetBackingThickness(9); }, "BackingThickness" },
    { "negative backing absorption", [](vtkOpalSource* s) { s->SetBackingAbsorption(-2); }, "BackingAbsorption" },
    { "NaN backing absorption", [](vtkOpalSource* s) { s->SetBackingAbsorption(std::nan("")); }, "BackingAbsorption" },
    { "negative domain scattering", [](vtkOpalSource* s) { s->SetDomainScatteringCoefficient(-0.5); },
      "DomainScatteringCoefficient" },
    { "huge domain scattering", [](vtkOpalSource* s) { s->SetDomainScatteringCoefficient(1e9); },
      "DomainScatteringCoefficient" },
    { "sphere index below 1", [](vtkOpalSource* s) { s->SetSphereRefractiveIndex(0.9); }, "SphereRefractiveIndex" },
    { "NaN matrix index", [](vtkOpalSource* s) { s->SetMatrixRefractiveIndex(std::nan("")); }, "MatrixRefractiveIndex" },
    { "matrix index 4", [](vtkOpalSource* s) { s->SetMatrixRefractiveIndex(4.0); }, "MatrixRefractiveIndex" },
    { "more voxels than memory", [](vtkOpalSource* s) { s->SetDimensions(4000, 4000, 4000); }, "of memory" },
  };
}

// Each bad case fails the request naming its parameter, and the same
// source works again once the parameter is fixed.
void checkBadCases()
{
  for (const BadCase& bad : badSourceCases())
  {
    auto source = opaltest::makeSmallSource();
    vtkNew<MessageRecorder> recorder;
    recorder->watch(source);
    bad.Break(source);
    const int status = source->GetExecutive()->Update();
    OPAL_CHECK(status == 0, bad.Description + ": the request fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, bad.Expected),
      bad.Description + ": the error names " + bad.Expected);
    // Fixed again, the same source works.
    auto fresh = opaltest::makeSmallSource();
    source->SetModelParameters(fresh->GetModelParameters());
    source->SetPreset(fresh->GetPreset());
    recorder->clear();
    OPAL_CHECK(source->GetExecutive()->Update() == 1 && recorder->Errors.empty(),
      bad.Description + ": the source recovers once fixed");
  }
}

// Placement that cannot do all it is asked warns and still builds.
void checkPlacementWarnings()
{
  // Far more big domains than fit: a warning naming DomainCount, the placed count, no hang.
  auto crowded = opaltest::makeSmallSource();
  crowded->SetDomainCount(400);
  crowded->SetDomainRadiusRange(2.5, 3.0);
  crowded->SetMaxPlacementAttempts(40);
  vtkNew<MessageRecorder> recorder;
  recorder->watch(crowded);
  OPAL_CHECK(crowded->GetExecutive()->Update() == 1, "a crowded opal still builds");
  OPAL_CHECK(recorder->anyContains(recorder->Warnings, "DomainCount"), "the warning names DomainCount");
  const double placed = crowded->GetOutput()->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0);
  OPAL_CHECK(placed > 0 && placed < 400, "DomainsPlaced says how many fit: " + std::to_string(placed));

  // A shape smaller than two voxels: it builds, with a warning naming SemiAxes.
  auto tiny = opaltest::makeSmallSource();
  tiny->SetSemiAxes(1e-6, 1e-6, 1e-6);
  tiny->SetDomainCount(0);
  recorder->clear();
  recorder->watch(tiny);
  OPAL_CHECK(tiny->GetExecutive()->Update() == 1, "a tiny opal still builds");
  OPAL_CHECK(recorder->anyContains(recorder->Warnings, "SemiAxes"), "a tiny opal warns naming SemiAxes");
}
} // namespace

int TestOpalBadInput(int, char*[])
{
  // The executive reports failed requests on the output window; keep the log readable.
  opaltest::silenceExpectedErrors();
  checkBadCases();
  {
    vtkNew<vtkOpalSource> source;
    OPAL_CHECK(!source->SetPresetByName("fig99"), "an unknown preset name is refused");
  }
  checkPlacementWarnings();
  return opaltest::finish("TestOpalBadInput");
}

