// A device lost is survived (docs/design.md §8.2): the test hook
// (VulkanContext::loseDeviceAtSubmitForTesting) makes a submit report
// VK_ERROR_DEVICE_LOST. The filter's request fails with one error naming it,
// and the next request renders on a new device the first image, array for
// array: a loss at the first submit of a frame, in its middle, after the
// input changed (the volume uploaded again) and in a background frame.
// A RenderSession throws DeviceLostError and a new one renders the same image.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVulkanContext.h"
#include "OpalVulkanError.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <chrono>
#include <string>
#include <thread>

namespace
{
// Whether every point array of `a` is in `b` with the same values.
bool sameArrays(vtkImageData* a, vtkImageData* b)
{
  vtkPointData* first = a->GetPointData();
  bool same = first->GetNumberOfArrays() > 0 && first->GetNumberOfArrays() == b->GetPointData()->GetNumberOfArrays();
  for (int i = 0; same && i < first->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* x = first->GetArray(i);
    vtkDataArray* y = b->GetPointData()->GetArray(x->GetName());
    same = y && x->GetNumberOfValues() == y->GetNumberOfValues();
    for (vtkIdType v = 0; same && v < x->GetNumberOfValues(); ++v)
    {
      same = x->GetVariantValue(v) == y->GetVariantValue(v);
    }
  }
  return same;
}

// The one error a request that met the loss reported.
void checkLossReported(opaltest::MessageRecorder* recorder, const std::string& when)
{
  OPAL_CHECK(recorder->Errors.size() == 1, when + ": one error (" + std::to_string(recorder->Errors.size()) + ")");
  OPAL_CHECK(recorder->anyContains(recorder->Errors, "The Vulkan device was lost (VK_ERROR_DEVICE_LOST)") &&
      recorder->anyContains(recorder->Errors, "the next render creates a new device"),
    when + ": it names the loss and what follows");
  recorder->clear();
}

// The update after the loss: no error, and the first image again.
void checkRecovered(vtkOpalSpectralRender* render, vtkImageData* first, opaltest::MessageRecorder* recorder,
  const std::string& when)
{
  OPAL_CHECK(render->GetExecutive()->Update() == 1 && recorder->Errors.empty(), when + ": the next update renders");
  OPAL_CHECK(sameArrays(first, render->GetOutput()), when + ": the first image, every array identical");
  recorder->clear();
}

void checkFilter()
{
  vtkNew<vtkOpalSource> source;
  source->SetDimensions(40, 20, 50);
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(80, 60);
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(render);
  OPAL_CHECK(render->GetExecutive()->Update() == 1, "the first update renders");
  vtkNew<vtkImageData> first;
  first->DeepCopy(render->GetOutput());

  // A frame's first submit, its second (the first went through), and the
  // first after the input changed (the volume is uploaded again).
  struct Loss
  {
    int Submit;
    bool InputChanged;
    std::string When;
  };
  for (const Loss& loss : { Loss{ 1, false, "lost at a frame's first submit" },
         Loss{ 2, false, "lost in the middle of a frame" }, Loss{ 1, true, "lost after the input changed" } })
  {
    const std::string& when = loss.When;
    loss.InputChanged ? source->Modified() : render->Modified();
    opal::VulkanContext::loseDeviceAtSubmitForTesting(loss.Submit);
    OPAL_CHECK(render->GetExecutive()->Update() == 0, when + ": the update fails");
    checkLossReported(recorder, when);
    checkRecovered(render, first, recorder, when);
  }

  // A background frame: the loss is said when the frame is taken, and the filter renders on.
  opal::VulkanContext::loseDeviceAtSubmitForTesting(1);
  OPAL_CHECK(render->StartBackgroundFrame(render->GetRenderParameters()), "a background frame starts");
  while (render->GetBackgroundFrameState() == 1)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  vtkNew<vtkImageData> image;
  OPAL_CHECK(!render->TakeBackgroundFrame(image), "the lost background frame gives no image");
  checkLossReported(recorder, "lost in a background frame");
  OPAL_CHECK(render->GetBackgroundFrameState() == 0, "no background frame is left");
  checkRecovered(render, first, recorder, "lost in a background frame");
  OPAL_CHECK(render->StartBackgroundFrame(render->GetRenderParameters()), "a new background frame starts");
  while (render->GetBackgroundFrameState() == 1)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  OPAL_CHECK(render->TakeBackgroundFrame(image) && sameArrays(first, image), "and gives the first image");
}

void checkSession()
{
  opaltest::SlabScene scene;
  scene.Dimensions = { 40, 10, 40 };
  scene.Spacing = 0.2;
  scene.Scattering = 2.0;
  scene.WithDomain = true;
  const opal::RenderVolume volume = scene.build();
  opal::RenderImage first;
  {
    opaltest::SceneRenderer renderer{ opal::VulkanOptions{} };
    first = renderer.render(volume, opaltest::slabView());
    opal::VulkanContext::loseDeviceAtSubmitForTesting(2);
    std::string error;
    try
    {
      renderer.Session.render(opaltest::slabView());
    }
    catch (const opal::DeviceLostError& e)
    {
      error = e.what();
    }
    OPAL_CHECK(error.find("VK_ERROR_DEVICE_LOST") != std::string::npos,
      "RenderSession::render throws DeviceLostError (" + error + ")");
  }
  opaltest::SceneRenderer renderer{ opal::VulkanOptions{} };
  const opal::RenderImage again = renderer.render(volume, opaltest::slabView());
  OPAL_CHECK(!first.RGB.empty() && again.RGB == first.RGB && again.Radiance == first.Radiance &&
      again.XYZ == first.XYZ && again.Depth == first.Depth,
    "a new session renders the same image");
  OPAL_CHECK(renderer.context().validationMessages().empty(), "the validation layer is silent");
}
} // namespace

int TestOpalDeviceLost(int, char*[])
{
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  opaltest::silenceExpectedErrors();
  checkFilter();
  checkSession();
  return opaltest::finish("TestOpalDeviceLost");
}
