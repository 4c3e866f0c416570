// Abort mid-way, as the GUI's stop button does, for the volume source and
// the render: each stops promptly (between slabs; within a tile of the
// march), the request fails without partial output, and the pipeline works
// normally once the abort is cleared.
#include "OpalTestHarness.h"
#include "OpalQuarterScaleRender.h"
#include "OpalRenderScenes.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"

#include <iostream>

int TestOpalAbort(int, char*[])
{
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  opaltest::silenceExpectedErrors();
  opaltest::QuarterScaleRender pipeline(320, 240);
  vtkOpalSpectralRender* render = pipeline.Render;
  vtkNew<opaltest::AbortOnProgress> abort;
  render->AddObserver(vtkCommand::ProgressEvent, abort);

  const int status = render->GetExecutive()->Update();
  const double stopSeconds = abort->secondsSinceAbort();
  OPAL_CHECK(abort->Aborted, "the abort was requested mid-render");
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

  // The volume source at paper scale.
  vtkNew<vtkOpalSource> volume;
  vtkNew<opaltest::AbortOnProgress> abortVolume;
  abortVolume->AbortAt = 0.5;
  volume->AddObserver(vtkCommand::ProgressEvent, abortVolume);
  OPAL_CHECK(volume->GetExecutive()->Update() == 0, "an aborted volume fails the request");
  OPAL_CHECK(abortVolume->Aborted && abortVolume->secondsSinceAbort() < 1.0, "the volume stops promptly");
  OPAL_CHECK(volume->GetOutput()->GetNumberOfPoints() == 0, "an aborted volume leaves no partial arrays");
  volume->RemoveObserver(abortVolume);
  volume->SetAbortExecute(0);
  volume->Modified();
  OPAL_CHECK(volume->GetExecutive()->Update() == 1 && volume->GetOutput()->GetNumberOfPoints() == 160 * 80 * 200,
    "the volume builds whole after the abort");
  return opaltest::finish("TestOpalAbort");
}
