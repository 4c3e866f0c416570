// Bench: the paper-scale frame (fig12, 160 x 80 x 200 voxels, 250 domains,
// 640 x 480 pixels, 41 wavelengths) on the default Vulkan device through a
// RenderSession (docs/design.md §5), printing each frame's split: the first
// frame (pipeline creation and, with a cold Mesa shader cache, the LLVM
// compile), warm frames, and a camera-only re-render (no upload, no light
// pass). Usage: opal-bench-render [WIDTH HEIGHT]
#include "OpalRenderSession.h"
#include "OpalVolumeBuild.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
void printFrame(const char* what, const opal::RenderFrame& frame, double seconds)
{
  const opal::RenderTimings& t = frame.Image.Timings;
  std::printf("  %-22s total %.3f s = setup %.3f + upload %.3f + light pass %.3f + march %.3f + colour %.3f + "
              "readback %.3f\n",
    what, seconds, t.Setup, t.Upload, t.LightPass, t.March, t.Colour, t.Readback);
}

double secondsOf(opal::RenderSession& session, const opal::RenderParameters& p, opal::RenderFrame& frame)
{
  const auto start = std::chrono::steady_clock::now();
  frame = session.render(p);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

int main(int argc, char** argv)
{
  opal::RenderParameters p; // the paper's set-up
  if (argc > 2)
  {
    p.ImageSize = { std::atoi(argv[1]), std::atoi(argv[2]) };
  }
  const auto volume = opal::buildVolume(opal::ModelParameters()); // fig12 at paper scale
  opal::RenderSession session;
  session.setVolume(volume->renderVolume());
  std::printf("opal render bench: fig12, 160x80x200 voxels, %dx%d pixels, on %s\n", p.ImageSize[0], p.ImageSize[1],
    session.context().deviceName().c_str());
  opal::RenderFrame frame;
  for (int run = 0; run < 3; ++run)
  {
    const double seconds = secondsOf(session, p, frame);
    printFrame(run == 0 ? "first frame" : ("frame " + std::to_string(run + 1)).c_str(), frame, seconds);
    p.LightPosition[0] = run % 2 ? 0.0 : 1e-3; // a new light: every frame runs the light pass
  }
  p.LightPosition[0] = 0.0;
  session.render(p);
  p.EyePosition = { 3.0, 59.9, 0.0 }; // only the camera moves
  const double seconds = secondsOf(session, p, frame);
  printFrame(frame.Ran.LightPass ? "camera-only (light!)" : "camera-only re-render", frame, seconds);
  std::printf("  goal: <= 0.5 s for the frame on lavapipe (paper: ~1350 s)\n");
  return 0;
}
