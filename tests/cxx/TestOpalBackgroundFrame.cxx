// A frame rendered on a worker thread (vtkOpalSpectralRender::StartBackgroundFrame,
// the live view's final frames, docs/design.md §5.2): it equals the frame an
// update renders, pixel for pixel; a cancel, a new background frame or an
// update abandons one still running and the session works on; the filter can
// end with one running; bad settings do not start one. The test command runs
// it under the sanitizers (scripts/opal.sh test).
#include "OpalQuarterScaleRender.h"
#include "OpalRenderParameters.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

namespace
{
// Waits for the background frame to finish: no bound but the test's timeout.
void waitForBackgroundFrame(vtkOpalSpectralRender* render)
{
  while (render->GetBackgroundFrameState() == 1)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// The largest difference between two images' RGB, or 256 if their sizes differ.
int largestDifference(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* first = a->GetPointData()->GetArray("RGB");
  vtkDataArray* second = b->GetPointData()->GetArray("RGB");
  if (!first || !second || first->GetNumberOfTuples() != second->GetNumberOfTuples())
  {
    return 256;
  }
  int largest = 0;
  for (vtkIdType i = 0; i < first->GetNumberOfValues(); ++i)
  {
    const int difference = static_cast<int>(first->GetVariantValue(i).ToInt() - second->GetVariantValue(i).ToInt());
    largest = std::max(largest, std::abs(difference));
  }
  return largest;
}
} // namespace

int TestOpalBackgroundFrame(int, char*[])
{
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  opaltest::silenceExpectedErrors();
  opaltest::QuarterScaleRender pipeline(160, 120);
  vtkOpalSource* source = pipeline.Source;
  vtkOpalSpectralRender* render = pipeline.Render;
  OPAL_CHECK(render->GetExecutive()->Update() == 1, "the update renders");

  // The same settings in the background: the same image.
  OPAL_CHECK(render->StartBackgroundFrame(render->GetRenderParameters()), "a background frame starts");
  waitForBackgroundFrame(render);
  vtkNew<vtkImageData> image;
  OPAL_CHECK(render->TakeBackgroundFrame(image), "the finished frame is taken");
  OPAL_CHECK(largestDifference(image, render->GetOutput()) == 0, "it equals the update's image pixel for pixel");
  OPAL_CHECK(render->GetBackgroundFrameState() == 0 && !render->TakeBackgroundFrame(image), "and is taken once");
  OPAL_CHECK(render->GetNumberOfCompletedBackgroundFrames() == 1, "one background frame completed");

  // A frame of 1280 x 960 takes seconds on lavapipe: each is cancelled well before its end.
  opal::RenderParameters big = render->GetRenderParameters();
  big.ImageSize = { 1280, 960 };
  OPAL_CHECK(render->StartBackgroundFrame(big), "a large frame starts");
  render->CancelBackgroundFrame();
  OPAL_CHECK(render->GetBackgroundFrameState() == 0, "a cancel ends it");
  OPAL_CHECK(render->StartBackgroundFrame(big) && render->StartBackgroundFrame(big), "a new one replaces it");
  render->Modified();
  OPAL_CHECK(render->GetExecutive()->Update() == 1, "an update while one runs renders");
  OPAL_CHECK(render->GetBackgroundFrameState() == 0, "and ends it");
  OPAL_CHECK(render->GetNumberOfAbandonedBackgroundFrames() == 3 && render->GetNumberOfCompletedBackgroundFrames() == 1,
    "three abandoned (" + std::to_string(render->GetNumberOfAbandonedBackgroundFrames()) + "), one completed");

  // Bad settings start nothing; the filter ends with a frame running.
  opal::RenderParameters bad = render->GetRenderParameters();
  bad.ViewAngle = 0;
  OPAL_CHECK(!render->StartBackgroundFrame(bad) && render->GetBackgroundFrameState() == 0, "bad settings start none");
  {
    vtkNew<vtkOpalSpectralRender> ending;
    ending->SetInputConnection(source->GetOutputPort(0));
    ending->SetImageSize(160, 120);
    ending->GetExecutive()->Update();
    big = ending->GetRenderParameters();
    big.ImageSize = { 1280, 960 };
    OPAL_CHECK(ending->StartBackgroundFrame(big), "a frame starts on a filter about to end");
  }
  return opaltest::finish("TestOpalBackgroundFrame");
}
