// What a preset implies for its render has one owner (opal::renderHints) and
// reaches a plain VTK pipeline as it reaches opal-render: a
// vtkOpalSpectralRender below a black-opal vtkOpalSource (with a filter
// between them, as ParaView puts one after every source) resolves the
// preset's image size, placement, Bragg model and lattice planes, equal to
// opal-render's parameters for that preset; a Bragg model other than the
// default, or PresetPlacement off, renders the properties as set; a saved volume's field data gives the same Bragg model
// and placement.
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderOptions.h"
#include "OpalTestHarness.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkImageChangeInformation.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"

namespace
{
opal::RenderParameters cliParameters(const char* preset)
{
  CLI::App app;
  OpalRenderOptions options;
  options.addTo(app);
  app.parse(std::vector<std::string>{});
  return options.parameters(preset, 1.45);
}
} // namespace

int TestOpalPresetHints(int, char*[])
{
  const int blackOpal = opal::presetIndexByName("black-opal");
  vtkNew<vtkOpalSource> source;
  source->SetPreset(blackOpal);
  source->SetDimensions(16, 8, 20);
  vtkNew<vtkImageChangeInformation> between; // a pass-through filter
  between->SetInputConnection(source->GetOutputPort(0));
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(between->GetOutputPort());
  render->UpdateInformation();

  const opal::RenderParameters followed = render->GetResolvedFrame(render->GetInputInformation(0, 0)).Parameters;
  const opal::RenderParameters cli = cliParameters("black-opal");
  OPAL_CHECK(followed.BraggModel == opal::BraggModelKind::CoupledWave &&
      followed.LatticePlanes == opal::LatticePlaneSet::Fcc,
    "a plain pipeline follows black-opal's coupled-wave model and fcc planes");
  OPAL_CHECK(followed.BraggModel == cli.BraggModel && followed.LatticePlanes == cli.LatticePlanes &&
      followed.ImageSize == cli.ImageSize && followed.PresetRotation == cli.PresetRotation,
    "the pipeline resolves what opal-render resolves for the preset");

  render->SetBraggModel(1); // coupled-wave with the (111) planes: not the default pair, used as set
  const opal::RenderParameters chosen = render->GetResolvedFrame(render->GetInputInformation(0, 0)).Parameters;
  OPAL_CHECK(chosen.BraggModel == opal::BraggModelKind::CoupledWave &&
      chosen.LatticePlanes == opal::LatticePlaneSet::Stacking111,
    "a Bragg model and planes other than the defaults are used as set");
  render->SetBraggModel(0);
  render->PresetPlacementOff();
  const opal::RenderParameters asSet = render->GetResolvedFrame(render->GetInputInformation(0, 0)).Parameters;
  OPAL_CHECK(asSet.BraggModel == opal::BraggModelKind::Paper && asSet.LatticePlanes == opal::LatticePlaneSet::Stacking111,
    "with PresetPlacement off the properties are used as set");

  // A saved volume: no pipeline information, its field data only.
  source->Update();
  vtkNew<vtkImageData> saved;
  saved->DeepCopy(source->GetOutput());
  vtkNew<vtkOpalSpectralRender> fromFile;
  fromFile->SetInputData(saved);
  fromFile->UpdateInformation();
  const opal::RenderParameters read = fromFile->GetResolvedFrame(fromFile->GetInputInformation(0, 0), saved).Parameters;
  OPAL_CHECK(read.BraggModel == cli.BraggModel && read.LatticePlanes == cli.LatticePlanes &&
      read.PresetRotation == cli.PresetRotation,
    "a saved volume's field data gives the preset's Bragg model, planes and placement");
  return opaltest::finish("TestOpalPresetHints");
}
