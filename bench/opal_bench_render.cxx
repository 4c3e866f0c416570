// Bench: the paper-scale frame (fig12, 160 x 80 x 200 voxels, 250 domains,
// 640 x 480 pixels, 41 wavelengths) on the default Vulkan device, printing the
// total and its split. The first render includes creating the pipelines.
#include "OpalRenderParameters.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv)
{
  const int width = argc > 2 ? std::atoi(argv[1]) : 640;
  const int height = argc > 2 ? std::atoi(argv[2]) : 480;
  vtkNew<vtkOpalSource> source; // fig12 at paper scale
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(width, height);
  source->Update();
  std::printf("opal render bench: fig12, 160x80x200 voxels, %dx%d pixels\n", width, height);
  for (int run = 0; run < 3; ++run)
  {
    render->Modified();
    const auto start = std::chrono::steady_clock::now();
    render->Update();
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    vtkImageData* image = render->GetOutput();
    vtkFieldData* fd = image->GetFieldData();
    vtkDataArray* t = fd->GetArray("RenderTimings");
    if (!t)
    {
      std::printf("render failed\n");
      return 1;
    }
    std::printf("  run %d on %s, %lld wavelengths: total %.3f s = setup %.3f + upload %.3f + light pass %.3f + "
                "march %.3f + colour %.3f + readback %.3f (+ VTK arrays)\n",
      run + 1, vtkStringArray::SafeDownCast(fd->GetAbstractArray("VulkanDevice"))->GetValue(0).c_str(),
      static_cast<long long>(fd->GetArray("Wavelengths")->GetNumberOfTuples()), total, t->GetComponent(0, 0),
      t->GetComponent(0, 1), t->GetComponent(0, 2), t->GetComponent(0, 3), t->GetComponent(0, 4),
      t->GetComponent(0, 5));
  }
  std::printf("  goal: <= 0.5 s for the frame on lavapipe (paper: ~1350 s)\n");
  return 0;
}
