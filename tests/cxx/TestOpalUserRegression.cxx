// "Using Opal in your own VTK tests" (README): a test as a user adds it to
// their own module. It builds an opal, renders it spectrally and compares the
// image with its baseline through VTK's regression testing: vtkTesting reads
// -V (the baseline) and -T (where a changed image is written) from the
// arguments vtk_add_test_cxx passes. vtkTesting compares an image algorithm's
// output directly, so no render window (and no display) is needed.
#include "vtkNew.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"
#include "vtkTesting.h"

#include <cstdlib>

int TestOpalUserRegression(int argc, char* argv[])
{
  vtkNew<vtkOpalSource> opal; // the paper's fig12 opal on a coarser grid
  opal->SetDimensions(80, 40, 100);
  vtkNew<vtkOpalSpectralRender> render; // its spectral render on Vulkan compute
  render->SetInputConnection(opal->GetOutputPort(0));
  render->SetImageSize(64, 48);
  render->SetExposure(5.0);
  vtkNew<vtkTesting> testing;
  testing->AddArguments(argc, argv);
  // The threshold of TestOpalRenderImages, where it is justified.
  return testing->RegressionTest(render, 0.5) == vtkTesting::PASSED ? EXIT_SUCCESS : EXIT_FAILURE;
}
