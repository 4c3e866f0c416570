// Bench: the Vulkan renderer against the reference renderer (the paper's
// algorithm followed literally, tests/reference) on the same machine in the
// same run. Both render the paper-scale fig12 volume (160 x 80 x 200, 250
// domains, 41 wavelengths) at a reduced 64 x 48 image; the reference is then
// extrapolated to the 640 x 480 frame by the pixel count (its cost is a sum
// over pixels of per-ray work on the same volume; the opal covers the same
// share of the frame at any resolution) and set against the measured Vulkan
// frame.
#include "OpalReferenceRenderer.h"
#include "OpalReferenceScene.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

namespace
{
double secondsOf(const std::function<void()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double vulkanSeconds(vtkOpalSource* source, int width, int height)
{
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(width, height);
  render->Update(); // the first render creates the pipelines
  // A light moved by a micrometre: the whole frame again, light pass included
  // (a render session would otherwise reuse the light field).
  render->SetLightPosition(0.001, 60.0, 0.0);
  return secondsOf([&] { render->Update(); });
}
} // namespace

int main(int argc, char** argv)
{
  const std::string cie = argc > 1 ? argv[1] : "vtkOpal/core/colour/data";
  vtkNew<vtkOpalSource> source; // fig12, paper scale
  source->Update();
  vtkImageData* volume = source->GetOutput();

  const opalreference::Scene scene = opalreference::sceneFromVolume(volume);

  const opalreference::View view; // 64 x 48, the paper's set-up
  const double referenceSmall = secondsOf([&] { opalreference::render(scene, view, cie); });
  const double vulkanSmall = vulkanSeconds(source, 64, 48);
  const double vulkanFrame = vulkanSeconds(source, 640, 480);
  const double referenceFrame = referenceSmall * 100.0; // 640 x 480 has 100 x the pixels
  std::printf("reference vs Vulkan, fig12 at paper scale, 41 wavelengths\n");
  std::printf("  64 x 48:   reference %.2f s (1 core), Vulkan %.3f s: %.0f x\n", referenceSmall, vulkanSmall,
    referenceSmall / vulkanSmall);
  std::printf("  640 x 480: reference %.0f s (extrapolated by pixel count), Vulkan %.2f s (measured): %.0f x "
              "(goal >= 300 x)\n",
    referenceFrame, vulkanFrame, referenceFrame / vulkanFrame);
  return 0;
}
