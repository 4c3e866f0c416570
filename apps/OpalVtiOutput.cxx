// The .vti output module of opal-render (OpalOutputModules.h): the rendered
// image with all its arrays, and the volume as the VTK source builds it.
#include "OpalOutputModules.h"
#include "OpalVtkSupport.h"
#include "vtkOpalRenderOutput.h"
#include "vtkOpalSource.h"

#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"

namespace
{
std::string writeImage(const opal::RenderImage& image, const std::string& deviceName, const std::string& path)
{
  vtkNew<vtkImageData> data;
  vtkOpalRenderOutput::Fill(image, deviceName, data);
  return writeImageDataFile(path, data);
}

std::string writeVolume(const opal::ModelParameters& parameters, int preset, const std::string& path)
{
  installStderrOutputWindow("opal-render");
  vtkNew<vtkOpalSource> source;
  // The preset first: choosing it sets its values, which the parameters then replace.
  source->SetPreset(preset);
  source->SetModelParameters(parameters);
  if (!source->GetExecutive()->Update())
  {
    return "the volume could not be built for " + path;
  }
  return writeImageDataFile(path, source->GetOutput());
}

const opal::VtiOutputModule module{ &writeImage, &writeVolume };
} // namespace

const opal::VtiOutputModule* opalVtiOutputModule()
{
  return &module;
}
