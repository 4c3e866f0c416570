// Bad input to the Bragg map: data without the opal's arrays gets an error
// naming the missing array; a light inside the opal is refused by name; a
// domain's NaN or zero Normal, NaN or negative ParticleDiameter and a
// one-component Normal are refused naming the array; the filter works again
// once fixed; the coupled-wave settings out of range are refused by name.
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"
#include "vtkOpalBraggMap.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace
{
// One bad value at the first domain voxel of a copy of the volume: the map must fail naming `expected`.
void checkBadDomainValue(vtkImageData* good, const std::string& what,
  const std::function<void(vtkImageData*, vtkIdType)>& spoil, const std::string& expected)
{
  vtkNew<vtkImageData> volume;
  volume->DeepCopy(good);
  vtkDataArray* ids = volume->GetPointData()->GetArray("DomainId");
  vtkIdType domainVoxel = 0;
  while (domainVoxel < ids->GetNumberOfTuples() && ids->GetComponent(domainVoxel, 0) < 0)
    ++domainVoxel;
  spoil(volume, domainVoxel);
  vtkNew<vtkOpalBraggMap> map;
  map->SetInputData(volume);
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(map);
  OPAL_CHECK(map->GetExecutive()->Update() == 0, what + ": the request fails");
  OPAL_CHECK(recorder->anyContains(recorder->Errors, expected), what + ": the message names " + expected);
}
} // namespace
#include "vtkOutputWindow.h"

int TestOpalBraggMapBadInput(int, char*[])
{
  opaltest::silenceExpectedErrors();
  opaltest::checkRefusesNonOpalVolume<vtkOpalBraggMap>("DomainId");
  {
    auto source = opaltest::makeSmallSource();
    vtkNew<vtkOpalBraggMap> map;
    map->SetInputConnection(source->GetOutputPort(0));
    vtkNew<opaltest::MessageRecorder> recorder;
    recorder->watch(map);
    map->SetLightPosition(0, 3, 0);
    OPAL_CHECK(map->GetExecutive()->Update() == 0, "a light inside the opal fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, "LightPosition"), "the message names LightPosition");
    recorder->clear();
    map->SetLightPosition(0, 60, 0);
    OPAL_CHECK(map->GetExecutive()->Update() == 1 && recorder->Errors.empty(), "the filter recovers once fixed");
    vtkNew<vtkImageData> good;
    good->DeepCopy(source->GetOutput());
    auto setNormal = [](double x) {
      return [x](vtkImageData* v, vtkIdType i) { v->GetPointData()->GetArray("Normal")->SetComponent(i, 0, x);
        v->GetPointData()->GetArray("Normal")->SetComponent(i, 1, x);
        v->GetPointData()->GetArray("Normal")->SetComponent(i, 2, x); };
    };
    auto setDiameter = [](double d) {
      return [d](vtkImageData* v, vtkIdType i) { v->GetPointData()->GetArray("ParticleDiameter")->SetComponent(i, 0, d); };
    };
    checkBadDomainValue(good, "NaN normal", setNormal(NAN), "Normal");
    checkBadDomainValue(good, "zero normal", setNormal(0.0), "Normal");
    checkBadDomainValue(good, "NaN particle diameter", setDiameter(NAN), "ParticleDiameter");
    checkBadDomainValue(good, "negative particle diameter", setDiameter(-5.0), "ParticleDiameter");
    // The coupled-wave settings (docs/design.md §7.3): fcc needs coupled-wave
    // and the volume's LatticeOrientation; CoherentLayers at least 1.
    auto refuses = [&](const std::string& what, const std::function<void(vtkOpalBraggMap*)>& set,
                     vtkImageData* input, const std::string& expected) {
      vtkNew<vtkOpalBraggMap> coupled;
      coupled->SetInputData(input);
      set(coupled);
      vtkNew<opaltest::MessageRecorder> watched;
      watched->watch(coupled);
      OPAL_CHECK(coupled->GetExecutive()->Update() == 0, what + ": the request fails");
      OPAL_CHECK(watched->anyContains(watched->Errors, expected), what + ": the message names " + expected);
    };
    refuses("fcc with the paper's model", [](vtkOpalBraggMap* m) { m->SetLatticePlanes(1); }, good, "LatticePlanes");
    refuses("no coherent layers", [](vtkOpalBraggMap* m) { m->SetBraggModel(1); m->SetCoherentLayers(0); }, good,
      "CoherentLayers");
    refuses("an unknown Bragg model", [](vtkOpalBraggMap* m) { m->SetBraggModel(7); }, good,
      "BraggModel must be 0 (paper) or 1 (coupled-wave), got 7");
    // A value that is not a choice is named as such, not as "needs coupled-wave".
    refuses("LatticePlanes 5", [](vtkOpalBraggMap* m) { m->SetLatticePlanes(5); }, good,
      "LatticePlanes must be 0 (111) or 1 (fcc), got 5");
    refuses("MosaicSpread 91", [](vtkOpalBraggMap* m) { m->SetMosaicSpread(91); }, good, "MosaicSpread");
    vtkNew<vtkImageData> unoriented;
    unoriented->DeepCopy(good);
    unoriented->GetPointData()->RemoveArray("LatticeOrientation");
    refuses("fcc without the lattice orientation", [](vtkOpalBraggMap* m) { m->SetBraggModel(1); m->SetLatticePlanes(1); },
      unoriented, "LatticeOrientation");
    checkBadDomainValue(good, "one-component normal", [](vtkImageData* v, vtkIdType) {
      vtkNew<vtkFloatArray> flat;
      flat->SetName("Normal");
      flat->SetNumberOfTuples(v->GetNumberOfPoints());
      flat->FillValue(1.0f);
      v->GetPointData()->AddArray(flat);
    }, "Normal");
  }
  return opaltest::finish("TestOpalBraggMapBadInput");
}
