// One frame resolution for every path (opal::resolveFrame, docs/design.md
// §3.2): a preview through the VTK filter is the render session's preview of
// the same volume and camera, value for value, with the preview's own stages
// (the per-voxel light read and the longer march step) reported by the session;
// and a preview differs from the final frame scaled down (so the check can fail).
#include "OpalQuarterScaleRender.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <vector>

namespace
{
// The filter's XYZ in the session's order (image rows top to bottom).
std::vector<float> topDownXYZ(vtkImageData* image)
{
  auto* xyz = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("XYZ"));
  int dimensions[3];
  image->GetDimensions(dimensions);
  std::vector<float> values;
  if (!xyz)
  {
    return values;
  }
  const vtkIdType row = static_cast<vtkIdType>(dimensions[0]) * 3;
  for (int y = dimensions[1] - 1; y >= 0; --y)
  {
    values.insert(values.end(), xyz->GetPointer(y * row), xyz->GetPointer(y * row) + row);
  }
  return values;
}
} // namespace

int TestOpalPreviewFrame(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  opaltest::QuarterScaleRender pipeline(160, 120);
  pipeline.Render->SetQuality(1);
  OPAL_CHECK(pipeline.Render->GetExecutive()->Update() == 1, "the filter renders a preview");
  const std::vector<float> filtered = topDownXYZ(pipeline.Render->GetOutput());

  const auto volume = opal::buildVolume(pipeline.Source->GetModelParameters());
  renderer->Session.setVolume(volume->renderVolume());
  const opal::ResolvedFrame resolved = pipeline.Render->GetResolvedFrame(pipeline.Render->GetInputInformation(0, 0));
  OPAL_CHECK(resolved.Preview && resolved.Parameters.ImageSize[0] == 80 && resolved.Parameters.ImageSize[1] == 60,
    "the filter resolves a preview of half the width and height");
  opal::RenderParameters asked = pipeline.Render->GetRenderParameters();
  asked.RefractiveIndex = pipeline.Source->GetModelParameters().RefractiveIndex; // the filter's 0: the volume's
  asked.ScatteringOrders = resolved.Parameters.ScatteringOrders;                 // the filter's volume: the preset's
  asked.Quality = opal::RenderQuality::Preview;
  const opal::RenderFrame preview = renderer->Session.render(asked);
  OPAL_CHECK(preview.Status == opal::FrameStatus::Completed && preview.Ran.Preview,
    "the session's preview completes and reports the preview's stages");
  OPAL_CHECK(!filtered.empty() && filtered == preview.Image.XYZ,
    "the filter's preview equals the session's preview value for value");

  // The final frame with the preview's reductions but not its stages is another image.
  opal::RenderParameters reducedFinal = opal::withQuality(asked);
  const opal::RenderFrame final = renderer->Session.render(reducedFinal);
  OPAL_CHECK(!final.Ran.Preview && final.Image.XYZ != preview.Image.XYZ,
    "a final frame of the preview's size runs the final stages and differs");
  const auto messages = renderer->context().validationMessages();
  OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  return opaltest::finish("TestOpalPreviewFrame");
}
