// Bad input to the Bragg map: data without the opal's arrays gets an error
// naming the missing array; a light inside the opal is refused by name; the
// filter works again once fixed.
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"
#include "vtkOpalBraggMap.h"

#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkRTAnalyticSource.h"

int TestOpalBraggMapBadInput(int, char*[])
{
  opaltest::silenceExpectedErrors();
  {
    vtkNew<vtkRTAnalyticSource> wavelet;
    vtkNew<vtkOpalBraggMap> map;
    map->SetInputConnection(wavelet->GetOutputPort());
    vtkNew<opaltest::MessageRecorder> recorder;
    recorder->watch(map);
    OPAL_CHECK(map->GetExecutive()->Update() == 0, "data without the opal arrays fails");
    OPAL_CHECK(recorder->anyContains(recorder->Errors, "DomainId"), "the message names the missing array DomainId");
  }
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
  }
  return opaltest::finish("TestOpalBraggMapBadInput");
}
