// Bench: the paper-scale frame (fig12, 160 x 80 x 200 voxels, 250 domains,
// 640 x 480 pixels, 41 wavelengths) on the default Vulkan device through a
// RenderSession (docs/design.md §5), printing frames' splits: the first
// frame (pipeline creation and, with a cold Mesa shader cache, the LLVM
// compile), then the medians of warm frames (7, each with a light pass),
// camera-only re-renders (7, no upload, no light pass) and preview frames (9),
// each with its median CPU time; the Bragg models, anti-aliasing and every
// order against the paper's frame; then the whole opal-render process (median
// of 5) with Mesa's shader cache warm and disabled. Usage: opal-bench-render [WIDTH HEIGHT]
#include "OpalRenderSession.h"
#include "OpalPresets.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <thread>
#include <vector>

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
// The median of some figures.
double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Median wall time of five runs of a shell command.
double medianSeconds(const std::string& command)
{
  std::vector<double> times;
  for (int run = 0; run < 5; ++run)
  {
    const auto start = std::chrono::steady_clock::now();
    if (std::system(command.c_str()) != 0)
    {
      return -1;
    }
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return median(times);
}

void benchProcess()
{
  std::error_code error;
  const std::filesystem::path bin = std::filesystem::read_symlink("/proc/self/exe", error).parent_path();
  const std::string render = (bin / "opal-render").string() + " --preset fig12 -o /tmp/opal-bench-render.png >/dev/null";
  std::printf("  opal-render process (fig12 to PNG, median of 5): warm shader cache %.3f s, "
              "cold (MESA_SHADER_CACHE_DISABLE=true) %.3f s\n",
    medianSeconds(render), medianSeconds("MESA_SHADER_CACHE_DISABLE=true " + render));
}

// The process's CPU seconds (all its threads: lavapipe's workers too).
double cpuSeconds()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// `count` frames, each after `vary`(p, run), which should (or should not)
// rerun the light pass; prints the median frame's split, the best and median
// totals (the machine is shared and noisy: one frame says little) and the
// median CPU time per frame, which a neighbour's load moves less than the
// wall clock (the figure to compare builds by on a busy hour).
template <typename Vary>
void benchFrames(const char* what, opal::RenderSession& session, opal::RenderParameters p, int count,
  bool lightPass, Vary vary)
{
  std::vector<std::pair<double, opal::RenderFrame>> frames(static_cast<std::size_t>(count));
  std::vector<double> cpu;
  for (int run = 0; run < count; ++run)
  {
    vary(p, run);
    auto& [seconds, frame] = frames[static_cast<std::size_t>(run)];
    const double cpuStart = cpuSeconds();
    seconds = secondsOf(session, p, frame);
    cpu.push_back(cpuSeconds() - cpuStart);
    if (frame.Ran.LightPass != lightPass)
    {
      std::printf("  %s: the light pass %s, unexpectedly\n", what, frame.Ran.LightPass ? "ran" : "did not run");
    }
  }
  std::sort(frames.begin(), frames.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const auto& middle = frames[frames.size() / 2];
  printFrame(what, middle.second, middle.first);
  std::printf("  %-22s (the median of %d; best %.3f s; CPU %.3f s a frame, median)\n", "", count,
    frames.front().first, median(cpu));
}

// The frame ticket (RenderSession::startFrame, docs/design.md §5: what
// opal-render and the live view's final frames use) against render() on the
// caller's thread, camera-only frames alternating, 7 each: the worker's cost.
void benchFrameTicket(opal::RenderSession& session, opal::RenderParameters p)
{
  std::vector<double> foreground, background;
  for (int run = 0; run < 14; ++run)
  {
    p.EyePosition = { run % 4 < 2 ? -3.0 : 3.0, 59.9, 0.0 };
    const auto start = std::chrono::steady_clock::now();
    if (run % 2 == 0)
    {
      session.render(p);
    }
    else
    {
      session.startFrame(opal::resolveFrame(p));
      while (session.backgroundState() == opal::BackgroundState::Running)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      session.takeFrame();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    (run % 2 == 0 ? foreground : background).push_back(seconds);
  }
  std::printf("  camera-only frame through the frame ticket %.3f s against render() %.3f s (x%.2f, medians of 7, "
              "alternating)\n",
    median(background), median(foreground), median(background) / median(foreground));
}

// The best of four full frames (each with its light pass) of the volume with
// the given Bragg model and planes (docs/design.md §7.2).
double bestFrame(opal::RenderSession& session, opal::RenderParameters p)
{
  opal::RenderFrame frame;
  session.render(p); // the pipeline
  double best = 1e30;
  for (int run = 0; run < 4; ++run) // the best of several: the bench machine is shared and noisy
  {
    p.LightPosition[0] = run % 2 ? 0.0 : 1e-3;
    best = std::min(best, secondsOf(session, p, frame));
  }
  return best;
}

// The Bragg models side by side: paper, coupled-wave, coupled-wave with the
// fcc planes, and the last with an absorbing body (the goal: at most
// 1.5 x the paper's frame).
void benchBraggModels(opal::RenderSession& session, opal::RenderParameters p)
{
  const double paper = bestFrame(session, p);
  p.BraggModel = opal::BraggModelKind::CoupledWave;
  const double coupled = bestFrame(session, p);
  p.LatticePlanes = opal::LatticePlaneSet::Fcc;
  const double fcc = bestFrame(session, p);
  opal::ModelParameters absorbing;
  absorbing.BodyAbsorption = 0.15;
  absorbing.BodyAbsorptionExponent = 6.0;
  const auto volume = opal::buildVolume(absorbing);
  session.setVolume(volume->renderVolume());
  const double fccAbsorbing = bestFrame(session, p);
  std::printf("  Bragg models, full frames: paper %.3f s, coupled-wave %.3f s (x%.2f), + fcc %.3f s (x%.2f), "
              "+ absorption %.3f s (x%.2f)\n",
    paper, coupled, coupled / paper, fcc, fcc / paper, fccAbsorbing, fccAbsorbing / paper);
}
// The sum of Y over the image: the light the stone sends to the eye.
double luminance(const opal::RenderImage& image)
{
  double sum = 0;
  for (std::size_t i = 1; i < image.XYZ.size(); i += 3)
  {
    sum += image.XYZ[i];
  }
  return sum;
}

// ScatteringOrders all against single (docs/design.md §3.10) on one preset's
// volume, alternating, medians of 5: frames with a new light (light pass and,
// for all, the every-order solve), camera-only frames, the solve's time, and
// the share of the light from orders beyond the first.
void benchScatteringOrders(opal::RenderSession& session, opal::RenderParameters p, int preset, const char* name)
{
  opal::ModelParameters model;
  model.applyPreset(preset);
  const auto volume = opal::buildVolume(model);
  session.setVolume(volume->renderVolume());
  const opal::VolumeRenderHints hints = opal::renderHints(preset, model.RefractiveIndex);
  p.BraggModel = hints.BraggModel.value_or(p.BraggModel);
  p.LatticePlanes = hints.LatticePlanes.value_or(p.LatticePlanes);
  p.Exposure = 1.0;
  std::vector<double> lit[2], camera[2], solve;
  double light[2] = { 0, 0 };
  opal::RenderFrame frame;
  for (int run = 0; run < 12; ++run)
  {
    const int all = run % 2;
    p.ScatteringOrders = all ? opal::ScatteringOrdersKind::All : opal::ScatteringOrdersKind::Single;
    p.LightPosition[0] = 1e-3 * (run / 2 + 1);
    p.EyePosition[0] = 0.0;
    const double litSeconds = secondsOf(session, p, frame);
    const double solveSeconds = frame.Image.Timings.ScatteredLight;
    light[all] = luminance(frame.Image);
    p.EyePosition[0] = 3.0;
    const double cameraSeconds = secondsOf(session, p, frame);
    if (run >= 2) // the first pair builds the pipelines
    {
      lit[all].push_back(litSeconds);
      camera[all].push_back(cameraSeconds);
      if (all)
        solve.push_back(solveSeconds);
    }
  }
  std::printf("  %s, ScatteringOrders all against single (alternating, medians of 5): frame with a new light "
              "%.3f s against %.3f s (x%.2f; the solve %.3f s), camera-only %.3f s against %.3f s (x%.2f); orders "
              "beyond the first carry %.1f%% of the stone's luminance\n",
    name, median(lit[1]), median(lit[0]), median(lit[1]) / median(lit[0]), median(solve), median(camera[1]),
    median(camera[0]),
    median(camera[1]) / median(camera[0]), 100.0 * (1.0 - light[0] / light[1]));
}
// Anti-aliased frames (PixelSamples 4, docs/design.md §3.4 item 8) against
// one ray per pixel: frames with a new light and camera-only frames,
// alternating, medians of 5 after a pair that builds the pipelines.
void benchPixelArea(opal::RenderSession& session, opal::RenderParameters p)
{
  std::vector<double> lit[2], camera[2];
  opal::RenderFrame frame;
  for (int run = 0; run < 12; ++run)
  {
    const int area = run % 2;
    p.PixelSamples = area ? 4 : 1;
    p.LightPosition[0] = 1e-3 * (run / 2 + 1);
    p.EyePosition[0] = 0.0;
    const double litSeconds = secondsOf(session, p, frame);
    p.EyePosition[0] = 3.0;
    const double cameraSeconds = secondsOf(session, p, frame);
    if (run >= 2)
    {
      lit[area].push_back(litSeconds);
      camera[area].push_back(cameraSeconds);
    }
  }
  std::printf("  PixelSamples 4 against 1 (alternating, medians of 5): frame with a new light %.3f s against "
              "%.3f s (x%.2f), camera-only %.3f s against %.3f s (x%.2f)\n",
    median(lit[1]), median(lit[0]), median(lit[1]) / median(lit[0]), median(camera[1]), median(camera[0]),
    median(camera[1]) / median(camera[0]));
}

// WIDTH or HEIGHT: the whole word in digits, at least 1 (atoi took "1x" as 1
// and "x" as 0); exits with a message otherwise.
int pixels(const char* word)
{
  int value = 0;
  const char* last = word + std::strlen(word);
  const auto [stop, error] = std::from_chars(word, last, value);
  if (stop == word || stop != last || error != std::errc() || value < 1)
  {
    std::fprintf(stderr, "opal-bench-render: WIDTH and HEIGHT must be whole numbers of pixels, got \"%s\"\n", word);
    std::exit(2);
  }
  return value;
}
} // namespace

int main(int argc, char** argv)
{
  opal::RenderParameters p; // the paper's set-up
  if (argc > 2)
  {
    p.ImageSize = { pixels(argv[1]), pixels(argv[2]) };
  }
  const auto volume = opal::buildVolume(opal::ModelParameters()); // fig12 at paper scale
  opal::RenderSession session;
  session.setVolume(volume->renderVolume());
  std::printf("opal render bench: fig12, 160x80x200 voxels, %dx%d pixels, on %s\n", p.ImageSize[0], p.ImageSize[1],
    session.context().deviceName().c_str());
  opal::RenderFrame frame;
  printFrame("first frame", frame, secondsOf(session, p, frame));
  // A new light each frame: every one runs the light pass.
  benchFrames("frame", session, p, 7, true,
    [](opal::RenderParameters& q, int run) { q.LightPosition[0] = run % 2 ? 0.0 : 1e-3; });
  p.LightPosition[0] = 0.0;
  session.render(p);
  // Only the camera moves: no upload, no light pass.
  const auto moveEye = [](opal::RenderParameters& q, int run) { q.EyePosition = { run % 2 ? -3.0 : 3.0, 59.9, 0.0 }; };
  benchFrames("camera-only re-render", session, p, 7, false, moveEye);
  benchFrameTicket(session, p);
  p.Quality = opal::RenderQuality::Preview;
  session.render(p); // the preview's pipeline
  benchFrames("preview, camera only", session, p, 9, false, moveEye);
  p.Quality = opal::RenderQuality::Final;
  p.EyePosition = { 0.0, 60.0, 0.0 };
  benchPixelArea(session, p);
  benchBraggModels(session, p);
  benchScatteringOrders(session, p, opal::presetIndexByName("fig12"), "fig12");
  benchScatteringOrders(session, p, opal::presetIndexByName("white-opal"), "white-opal");
  std::printf("  goals (lavapipe, 2 cores): frame <= 0.45 s, camera-only <= 0.35 s, preview <= 0.1 s, "
              "process <= 1.0 s\n");
  benchProcess();
  return 0;
}
