// Abort mid-render, as the GUI's stop button does: the filter stops promptly
// (within a tile of the march), the request fails without an image, and the
// pipeline renders normally once the abort is cleared.
#include "OpalTestHarness.h"
#include "OpalRenderScenes.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkCallbackCommand.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"

#include <chrono>
#include <iostream>

namespace
{
struct AbortState
{
  double AbortAt = 0.3;
  bool Aborted = false;
  std::chrono::steady_clock::time_point When;
};

void abortOnProgress(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* state = static_cast<AbortState*>(clientData);
  if (!state->Aborted && *static_cast<double*>(callData) >= state->AbortAt)
  {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    state->Aborted = true;
    state->When = std::chrono::steady_clock::now();
  }
}
} // namespace

int main()
{
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::SkipReturnCode;
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkNew<vtkOpalSource> source;
  source->SetDimensions(80, 40, 100);
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(320, 240);
  AbortState state;
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback(abortOnProgress);
  abort->SetClientData(&state);
  render->AddObserver(vtkCommand::ProgressEvent, abort);

  const int status = render->GetExecutive()->Update();
  const double stopSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - state.When).count();
  OPAL_CHECK(state.Aborted, "the abort was requested mid-render");
  OPAL_CHECK(status == 0, "an aborted render fails the request");
  OPAL_CHECK(render->GetOutput()->GetNumberOfPoints() == 0, "an aborted render leaves no partial image");
  OPAL_CHECK(stopSeconds < 2.0, "the render stops promptly: " + std::to_string(stopSeconds) + " s after the abort");

  render->RemoveObserver(abort);
  render->SetAbortExecute(0);
  render->Modified();
  OPAL_CHECK(render->GetExecutive()->Update() == 1, "the pipeline renders again after the abort");
  int dims[3];
  render->GetOutput()->GetDimensions(dims);
  OPAL_CHECK(dims[0] == 320 && dims[1] == 240, "and the image is whole");
  return opaltest::finish("TestOpalRenderAbort");
}
