// opal-render: builds the opal volume and renders it spectrally on Vulkan
// compute, writing PNG (sRGB) and/or OpenEXR (linear) images. The VTK
// pipeline is not loaded: OpalCore builds the volume and a RenderSession
// renders it; the image and .vti writers are modules loaded when used.
#include "OpalAtomicFile.h"
#include "OpalCliFiles.h"
#include "OpalCliSupport.h"
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalOutputModules.h"
#include "OpalParameterList.h"
#include "OpalRenderOptions.h"
#include "OpalRenderParameters.h"
#include "OpalRenderSession.h"
#include "OpalVolumeBuild.h"
#include "OpalVulkanError.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace
{
// Ctrl-C stopped the render.
struct Interrupted : std::runtime_error
{
  Interrupted()
    : std::runtime_error("interrupted; nothing is written")
  {
  }
};

struct Outputs
{
  std::vector<std::string> Images;
  std::string Volume, ImageData;
  bool SpectralChannels = false;
};

void addOutputOptions(CLI::App& app, Outputs& outputs)
{
  app.add_option("-o,--output", outputs.Images,
       "Image file(s); the format follows the extension: .png (.tif, .jpg) sRGB 8-bit, .exr linear float")
    ->check(fileExtension({ ".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg" }))
    ->group("Output");
  app.add_flag("--exr-spectral-channels", outputs.SpectralChannels, "Also write one EXR channel per wavelength")
    ->group("Output");
  app.add_option("--save-volume", outputs.Volume, "Also write the volume as .vti")
    ->check(fileExtension({ ".vti" }))
    ->group("Output");
  app.add_option("--save-image", outputs.ImageData, "Also write the image with all its arrays as .vti")
    ->check(fileExtension({ ".vti" }))
    ->group("Output");
  app.add_flag_callback(
       "--list-parameters",
       [] {
         std::cout << parameterListJson() << std::endl;
         throw CLI::Success();
       },
       "Print every model and render parameter (name, type, range, flag, default, description) as JSON and exit")
    ->group("Output");
}

// Every output file with the flag that names it, in the order written.
std::vector<OutputName> outputNames(const Outputs& outputs)
{
  std::vector<OutputName> names;
  for (const std::string& path : outputs.Images)
  {
    names.push_back({ "-o", path });
  }
  for (const OutputName& vti : { OutputName{ "--save-image", outputs.ImageData }, OutputName{ "--save-volume", outputs.Volume } })
  {
    if (!vti.Path.empty())
    {
      names.push_back(vti);
    }
  }
  return names;
}

// Builds the volume with only the arrays the render reads
// (VolumeArrays::Render: no description), warning about a small shape or
// domains that could not be placed; nothing where `keepBuilding` said stop.
std::optional<opal::BuiltVolume> buildRenderVolume(
  const opal::ModelParameters& model, const std::function<bool()>& keepBuilding)
{
  ProgressBar volumeBar("volume");
  std::optional<opal::BuiltVolume> volume = opal::buildVolume(
    model,
    [&](double fraction) {
      volumeBar.show(fraction);
      return keepBuilding();
    },
    opal::VolumeArrays::Render);
  if (!volume)
  {
    return std::nullopt;
  }
  if (const std::string small = opal::smallShapeWarning(model); !small.empty())
  {
    std::cerr << "opal-render: " << small << std::endl;
  }
  if (volume->Layout.placedCount() < volume->Layout.requestedCount())
  {
    std::cerr << "opal-render: DomainCount: only " << volume->Layout.placedCount() << " of "
              << volume->Layout.requestedCount() << " domains could be placed within MaxPlacementAttempts."
              << std::endl;
  }
  return volume;
}

// Renders on the session's worker (its frame ticket) while this thread shows
// the progress and watches for Ctrl-C, which cancels the frame: nothing is
// written then, and the program exits with 130.
opal::RenderFrame renderInBackground(opal::RenderSession& session, const opal::RenderParameters& parameters)
{
  static volatile std::sig_atomic_t interrupted = 0;
  interrupted = 0;
  const auto previous = std::signal(SIGINT, [](int) { interrupted = 1; });
  ProgressBar renderBar("render");
  session.startFrame(opal::resolveFrame(parameters));
  while (session.backgroundState() == opal::BackgroundState::Running && !interrupted)
  {
    renderBar.show(session.backgroundProgress());
    std::this_thread::sleep_for(std::chrono::milliseconds(5)); // the frame is taken within 5 ms of its end
  }
  std::signal(SIGINT, previous);
  if (interrupted)
  {
    session.cancelFrame();
    throw Interrupted();
  }
  std::optional<opal::RenderFrame> frame = session.takeFrame(); // rethrows the worker's exception
  renderBar.show(1.0);
  return std::move(*frame);
}

// Builds the volume and renders the frame; throws on failure. The Vulkan
// device starts on a thread of its own while the volume builds (the loader,
// the driver and the pipelines: about 0.1 s of one core on lavapipe).
opal::RenderImage renderFrame(const opal::ModelParameters& model, const opal::RenderParameters& parameters,
  const OpalRenderOptions& options, std::string& deviceName)
{
  opal::VulkanOptions vulkan;
  vulkan.DeviceIndex = options.deviceIndex();
  vulkan.MemoryLimitBytes = static_cast<std::uint64_t>(std::max(0, options.deviceMemoryLimit())) << 20;
  std::future<std::unique_ptr<opal::RenderSession>> starting =
    std::async(std::launch::async, [vulkan] { return std::make_unique<opal::RenderSession>(vulkan); });
  // Once started, the device refuses a volume whose fields cannot fit
  // before the volume is built (a 10 um stone: minutes), or before it is
  // uploaded where the build finished first.
  std::unique_ptr<opal::RenderSession> session;
  std::exception_ptr refused;
  auto checkDevice = [&](bool wait) {
    if (!session && !refused && (wait || starting.wait_for(std::chrono::seconds(0)) == std::future_status::ready))
    {
      try
      {
        session = starting.get();
        session->checkVolumeFits(model.Dimensions, model.absorbs(), parameters);
      }
      catch (...)
      {
        refused = std::current_exception();
      }
    }
    return !refused;
  };
  const std::optional<opal::BuiltVolume> volume = buildRenderVolume(model, [&] { return checkDevice(false); });
  if (!checkDevice(true))
  {
    std::rethrow_exception(refused);
  }
  if (!volume)
  {
    throw std::runtime_error("the volume could not be built");
  }
  session->setVolume(volume->renderVolume());
  opal::RenderFrame frame = renderInBackground(*session, parameters); // its image is moved out below
  deviceName = session->context().deviceName();
  // With OPAL_VULKAN_VALIDATION set, what the validation layer said is shown, and fails the run.
  const std::vector<std::string> messages = session->context().validationMessages();
  for (const std::string& message : messages)
  {
    std::cerr << "opal-render: validation layer: " << message << std::endl;
  }
  if (!messages.empty())
  {
    throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(messages.size()) +
      " message(s); nothing is written");
  }
  return std::move(frame.Image);
}

// Writes every output, all or none: false (with one line on stderr) at the
// first failure, the files already replaced then restored.
bool writeOutputs(const Outputs& outputs, const opal::RenderImage& image, const std::string& deviceName,
  const OpalModelOptions& model, std::vector<std::string>& written)
{
  std::vector<std::filesystem::path> targets;
  for (const OutputName& output : outputNames(outputs))
  {
    targets.emplace_back(output.Path);
  }
  const SignalsHeld held; // released after the transaction below has committed or restored
  FileSetTransaction transaction(targets);
  auto record = [&](const std::string& path, const std::string& error) {
    if (!error.empty())
    {
      std::cerr << "opal-render: " << error << std::endl;
      return false;
    }
    written.push_back(path);
    return true;
  };
  for (const std::string& path : outputs.Images)
  {
    if (!record(path, opal::imageOutputModule(path).WriteImage(image, path, outputs.SpectralChannels)))
    {
      return false;
    }
  }
  if (!outputs.ImageData.empty() &&
    !record(outputs.ImageData, opal::vtiOutputModule().WriteImage(image, deviceName, outputs.ImageData)))
  {
    return false;
  }
  if (!outputs.Volume.empty() &&
    !record(outputs.Volume, opal::vtiOutputModule().WriteVolume(model.parameters(), model.presetIndex(), outputs.Volume)))
  {
    return false;
  }
  transaction.commit();
  return true;
}

void printSummary(const std::string& preset, const opal::RenderImage& image, const std::string& deviceName,
  double seconds, const std::vector<std::string>& written)
{
  const opal::RenderTimings& t = image.Timings;
  std::printf("Opal render (preset %s): %d x %d pixels, %zu wavelengths on %s\n", preset.c_str(), image.Region[2],
    image.Region[3], image.Wavelengths.size(), deviceName.c_str());
  std::printf("  render: setup %.3f s, upload %.3f s, light pass %.3f s, scattered light %.3f s, march %.3f s, "
              "colour %.3f s, readback %.3f s\n",
    t.Setup, t.Upload, t.LightPass, t.ScatteredLight, t.March, t.Colour, t.Readback);
  std::printf("  scattering orders: %s\n", image.ScatteringOrders.c_str());
  if (!image.Warning.empty())
  {
    std::fprintf(stderr, "opal-render: warning: %s\n", image.Warning.c_str());
  }
  std::printf("  exposure %.4g, total %.3f s\n", image.Exposure, seconds);
  for (const std::string& path : written)
  {
    std::printf("  written: %s\n", path.c_str());
  }
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "Builds the volumetric opal model of Nakajima & Kawai and renders it spectrally "
                "(Rayleigh scattering, Bragg diffraction) on Vulkan compute." };
  OpalModelOptions model;
  model.addTo(app);
  OpalRenderOptions render;
  render.addTo(app);
  Outputs outputs;
  addOutputOptions(app, outputs);
  app.failure_message([](const CLI::App* a, const CLI::Error& e) { return oneLineFailure("opal-render", e.what(), a); });
  if (const int status = parseArguments(app, argc, argv); status >= 0)
  {
    return status;
  }
  if (outputs.Images.empty() && outputs.ImageData.empty())
  {
    std::cerr << "opal-render: nothing to write; give -o FILE.png (or .exr) or --save-image FILE.vti" << std::endl;
    return 2;
  }
  // Two outputs that are one file would be written twice, and a later failed
  // write would take the earlier one's file with it: refused before any work.
  if (const std::string shared = sharedFileError(outputNames(outputs)); !shared.empty())
  {
    std::cerr << "opal-render: " << shared << std::endl;
    return 2;
  }
  opal::RenderParameters parameters = render.parameters(model.presetName(), model.refractiveIndex());
  parameters.WriteSpectrum = outputs.SpectralChannels || !outputs.ImageData.empty();
  // Bad parameters cost one line and exit status 2, before any work.
  for (const std::string& error :
    { opal::validate(model.parameters()), opal::volumeMemoryError(model.parameters(), opal::VolumeArrays::Render), opal::validate(parameters) })
  {
    if (!error.empty())
    {
      std::cerr << "opal-render: " << error << std::endl;
      return 2;
    }
  }
  // A full disk or a file-size limit then fails the write (and is reported)
  // instead of killing the process half way through a file.
  std::signal(SIGXFSZ, SIG_IGN);
  const auto start = std::chrono::steady_clock::now();
  try
  {
    std::string deviceName;
    const opal::RenderImage image = renderFrame(model.parameters(), parameters, render, deviceName);
    std::vector<std::string> written;
    if (!writeOutputs(outputs, image, deviceName, model, written))
    {
      return 1;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    printSummary(model.presetName(), image, deviceName, seconds, written);
    return 0;
  }
  catch (const Interrupted& e)
  {
    std::cerr << "opal-render: " << e.what() << std::endl;
    return 130;
  }
  catch (const opal::NoVulkanDeviceError& e)
  {
    std::cerr << "opal-render: No Vulkan device: " << e.what() << std::endl;
  }
  catch (const std::invalid_argument& e)
  {
    std::cerr << "opal-render: " << e.what() << std::endl;
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "opal-render: " << e.what() << std::endl;
  }
  return 1;
}
