// The render session keeps what a frame can reuse (docs/design.md §5): a
// second frame with only the camera changed runs neither the upload nor the
// light pass and gives exactly the image of a fresh session rendering that
// camera; a new light, rotation or refractive index reruns the light pass; an
// aborted light pass leaves no stale field behind; abort is an explicit status;
// the volume uploaded through staging buffers (the path of a GPU with
// dedicated memory, forced on lavapipe) renders the same image, a volume too
// large for one staging round too; so does a
// build of only the render's arrays (opal-render's, VolumeArrays::Render);
// runs of bytes read and written together (readRuns, writeRuns) through
// staging in batches.
#include "OpalRenderScenes.h"
#include "OpalShareMeeting.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"
#include "OpalVulkanBuffer.h"
#include "OpalVulkanContext.h"
#include "OpalVulkanError.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace
{
opal::RenderParameters smallView()
{
  opal::RenderParameters p;
  p.ImageSize = { 48, 36 };
  return p;
}

std::string stages(const opal::FrameStages& ran)
{
  std::string s;
  for (auto [name, on] : { std::pair<const char*, bool>{ "upload", ran.Upload }, { "light", ran.LightPass },
         { "scattered", ran.ScatteredLight }, { "exposure", ran.Exposure }, { "march", ran.March }, { "colour", ran.Colour }, { "readback", ran.Readback } })
  {
    s += on ? std::string(" ") + name : "";
  }
  return "ran:" + s;
}
// The path of a GPU with dedicated memory, forced on lavapipe.
void checkStagingTransfers(const opal::RenderVolume& volume, const opal::RenderParameters& p,
  const opal::RenderImage& expected, const std::string& rounds = "one copy")
{
  opal::VulkanOptions staging;
  staging.Validation = true;
  staging.StagingTransfers = true;
  opaltest::SceneRenderer throughStaging(staging);
  const opal::RenderImage image = throughStaging.render(volume, p);
  OPAL_CHECK(opaltest::identical(expected, image),
    "a volume uploaded and an image read back through staging buffers (" + rounds + ") give the same image");
  const auto messages = throughStaging.context().validationMessages();
  OPAL_CHECK(messages.empty(),
    "the validation layer is silent about the staging copies" + (messages.empty() ? "" : ": " + messages.front()));
}
} // namespace

// Every order (docs/design.md §3.10): the field is solved once per light, a
// camera-only frame and a preview with a moved light (the headlight's drag)
// keep it, a final frame with a new light solves it again, and single
// scattering never solves it.
void checkScatteredLightStages(opal::RenderSession& session, opal::RenderParameters p)
{
  p.ScatteringOrders = opal::ScatteringOrdersKind::All;
  p.ScatteringPhotons = 2000;
  const auto ran = [&session](const opal::RenderParameters& q) { return session.render(q).Ran; };
  const opal::FrameStages first = ran(p);
  OPAL_CHECK(first.ScatteredLight, "the first frame with every order solves the field (" + stages(first) + ")");
  p.EyePosition = { -8.0, 58.0, 6.0 };
  const opal::FrameStages camera = ran(p);
  OPAL_CHECK(!camera.ScatteredLight && !camera.LightPass, "a camera-only frame keeps it (" + stages(camera) + ")");
  p.LightPosition = { 4.0, 60.0, 0.0 };
  p.Quality = opal::RenderQuality::Preview;
  const opal::FrameStages preview = ran(p);
  OPAL_CHECK(!preview.ScatteredLight && preview.LightPass,
    "a preview with a moved light reads the held field (" + stages(preview) + ")");
  p.Quality = opal::RenderQuality::Final;
  const opal::FrameStages final = ran(p);
  OPAL_CHECK(final.ScatteredLight, "the final frame solves for its light (" + stages(final) + ")");
  p.ScatteringOrders = opal::ScatteringOrdersKind::Single;
  p.LightPosition = { -4.0, 60.0, 0.0 };
  const opal::FrameStages single = ran(p);
  OPAL_CHECK(!single.ScatteredLight, "single scattering solves nothing (" + stages(single) + ")");
}

// The field solved ahead of its frame, in three shares put together (as MPI
// ranks share the solve, docs/design.md §8.1: each reads back its slab of the
// medium, and the slabs go to every share), by sessions that have rendered
// nothing yet (a rank's first update), then the frame: the image a frame's
// own solve gives, pixel for pixel. (Its field per voxel was once written
// before the session's buffers were bound, so not at all.) Either way the
// progress only rises, to 1 (the frame's light pass and solve once both
// reported from 0 to 0.2, as did the shared solve and then the frame).
bool risesToOne(const std::vector<double>& seen)
{
  return !seen.empty() && std::is_sorted(seen.begin(), seen.end()) && seen.back() == 1.0;
}

void checkSharedSolve(opal::RenderSession& rendered, const opal::RenderVolume& volume, opal::RenderParameters p)
{
  p.ScatteringOrders = opal::ScatteringOrdersKind::All;
  p.ScatteringPhotons = 2000;
  p.LightPosition = { 2.0, 60.0, 1.0 };
  std::vector<double> seen;
  const opal::RenderProgress record = [&seen](double fraction) {
    seen.push_back(fraction);
    return true;
  };
  const opal::RenderImage own = rendered.render(p, record).Image;
  OPAL_CHECK(risesToOne(seen), "a frame's progress through its light pass and solve only rises, to 1");
  seen.clear();
  // Sessions that have rendered nothing, as ranks' first updates, on threads:
  // each reads back its slab of the medium (share 1 through staging buffers,
  // as a discrete GPU does) and the slabs go between them.
  constexpr int Shares = 3;
  std::vector<std::unique_ptr<opaltest::SceneRenderer>> sessions;
  for (int share = 0; share < Shares; ++share)
  {
    opal::VulkanOptions options;
    options.StagingTransfers = share == 1;
    sessions.push_back(std::make_unique<opaltest::SceneRenderer>(options));
    sessions.back()->Session.setVolume(volume);
  }
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  std::vector<opal::RenderSession*> shares;
  for (const auto& session : sessions)
  {
    shares.push_back(&session->Session);
  }
  const std::vector<bool> solved = opaltest::solveTogether(shares, frame, record);
  OPAL_CHECK(std::all_of(solved.begin(), solved.end(), [](bool s) { return s; }),
    "every share of a solve ahead of its frame holds the field");
  const opal::RenderFrame ahead = sessions.front()->Session.render(frame, record);
  OPAL_CHECK(opaltest::identical(own, ahead.Image), "a field solved ahead of its frame gives the frame's own image");
  OPAL_CHECK(risesToOne(seen), "the progress of a solve ahead of its frame, then the frame's, only rises, to 1");
  for (int share = 1; share < Shares; ++share)
  {
    OPAL_CHECK(opaltest::identical(own, sessions[static_cast<std::size_t>(share)]->Session.render(frame).Image),
      "share " + std::to_string(share) + "'s field, from the slabs it received, gives the frame's own image");
  }
  // A share failing before the medium's rounds (its session holds no volume)
  // sends its last instead: every share's rounds end, none waits, none holds a field.
  opaltest::SceneRenderer empty(opal::VulkanOptions{});
  std::vector<std::unique_ptr<opaltest::SceneRenderer>> again;
  for (int held = 0; held < 2; ++held) // shares 0 and 2
  {
    again.push_back(std::make_unique<opaltest::SceneRenderer>(opal::VulkanOptions{}));
    again.back()->Session.setVolume(volume);
  }
  const std::vector<bool> stopped =
    opaltest::solveTogether({ &again[0]->Session, &empty.Session, &again[1]->Session }, frame, nullptr);
  OPAL_CHECK(std::none_of(stopped.begin(), stopped.end(), [](bool s) { return s; }),
    "a share failing before the medium's rounds ends every share's solve, none holding a field");
  OPAL_CHECK(again[0]->Session.needsScatteredLight(frame), "the shares' frames then solve alone");
}

// Where the device's budget cannot hold the every-order field per voxel (16
// bytes a voxel), the march evaluates its tally grid instead
// (docs/design.md §3.10): the light pass writes the field with the same
// function, so the image is the field's pixel for pixel, and the field is
// freed before a larger frame's images are made. Under a budget between a
// small frame's needs and a large one's: the small frame reads the field,
// the large one the grid, and so does the small one after it, beside the
// larger image buffers the session keeps.
void checkScatteredLightFromGrid(const opal::RenderVolume& volume, opal::RenderParameters p)
{
  p.ScatteringOrders = opal::ScatteringOrdersKind::All;
  p.ScatteringPhotons = 2000;
  p.LightPosition = { 2.0, 60.0, 1.0 };
  opal::RenderParameters large = p;
  large.ImageSize = { 128, 96 };
  opaltest::SceneRenderer whole(opal::VulkanOptions{});
  const opal::RenderImage small = whole.render(volume, p);
  const std::uint64_t smallPeak = whole.Session.context().memoryPeak();
  const opal::RenderFrame wide = whole.Session.render(large);
  const std::uint64_t widePeak = whole.Session.context().memoryPeak();
  const std::uint64_t fieldBytes = volume.voxelCount() * 4 * sizeof(float);
  opal::VulkanOptions options;
  options.MemoryLimitBytes = widePeak - fieldBytes / 2;
  OPAL_CHECK(smallPeak <= options.MemoryLimitBytes && !wide.Ran.ScatteredLightFromGrid,
    "set-up: the small frame and its field fit the limit, the large one read the field unlimited");
  opaltest::SceneRenderer tight(options);
  opal::RenderSession& session = tight.Session;
  session.setVolume(volume);
  const opal::RenderFrame a = session.render(p);
  OPAL_CHECK(!a.Ran.ScatteredLightFromGrid && opaltest::identical(a.Image, small), "a frame whose field fits reads it");
  const opal::RenderFrame b = session.render(large);
  OPAL_CHECK(b.Ran.ScatteredLightFromGrid && opaltest::identical(b.Image, wide.Image),
    "a frame whose field does not fit evaluates the grid, and gives the field's image");
  OPAL_CHECK(session.context().memoryPeak() <= widePeak - fieldBytes + 4 * sizeof(float), // its placeholder's vec4
    "the field was freed before the larger images: peak " + std::to_string(session.context().memoryPeak()) +
      " bytes against " + std::to_string(widePeak) + " with the field");
  const opal::RenderFrame c = session.render(p);
  OPAL_CHECK(c.Ran.ScatteredLightFromGrid && opaltest::identical(c.Image, small),
    "beside the kept larger images the small frame evaluates the grid too, with the same image");
  const auto messages = session.context().validationMessages();
  OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
}

// The choice counts the Bragg shadow field the session keeps once energy
// conservation made it (12 bytes a voxel): under a limit that holds the
// field per voxel without the shadows but not beside them, a frame after
// energy conservation is turned off evaluates the grid (allocating the field
// there would exceed the limit) and gives the unlimited session's image.
void checkKeptShadowsCounted(const opal::RenderVolume& volume, opal::RenderParameters p)
{
  p.ScatteringOrders = opal::ScatteringOrdersKind::All;
  p.ScatteringPhotons = 2000;
  p.LightPosition = { 2.0, 60.0, 1.0 };
  opal::RenderParameters conserving = p;
  conserving.EnergyConservation = true;
  opaltest::SceneRenderer whole(opal::VulkanOptions{});
  const opal::RenderImage plain = whole.render(volume, p);
  opal::VulkanOptions options;
  options.MemoryLimitBytes = whole.Session.context().memoryPeak() + volume.voxelCount() * 6;
  opaltest::SceneRenderer tight(options);
  tight.Session.setVolume(volume);
  const opal::RenderFrame a = tight.Session.render(conserving);
  const opal::RenderFrame b = tight.Session.render(p);
  OPAL_CHECK(a.Ran.ScatteredLightFromGrid && b.Ran.ScatteredLightFromGrid && opaltest::identical(b.Image, plain),
    "beside the kept Bragg shadows, every order after energy conservation evaluates the grid, the same image");
}

// Where the device's budget does not hold SurfaceDistance and the light
// fields as pairs beside the Bragg shadows, the session holds one value per
// voxel read by address (docs/design.md §3.7), and the passes read the
// neighbour a pair would hold from the next voxel: each image equals the
// paired session's pixel for pixel, with the light above (the layer sweep)
// and at the side (the per-voxel march), in the preview (nearest reads) and
// with every order (its solve reads SurfaceDistance back), in an absorbing
// body; the device holds 20 bytes a voxel less. A device that cannot address
// buffers keeps the pairs bound, the same images.
void checkUnpairedFields(const opal::RenderVolume& volume, const opal::RenderParameters& p)
{
  std::vector<opal::RenderParameters> frames(4, p);
  frames[1].LightPosition = { 30.0, 12.0, 4.0 };
  frames[2].Quality = opal::RenderQuality::Preview;
  frames[3].ScatteringOrders = opal::ScatteringOrdersKind::All;
  frames[3].ScatteringPhotons = 2000;
  opaltest::SceneRenderer paired(opal::VulkanOptions{});
  paired.Session.setVolume(volume);
  // Pairs: VoxelCell 8, SurfaceDistance 8, light field 16, absorption cells 8
  // and their light field 16; the Bragg shadows 12.
  std::vector<opal::RenderImage> images;
  for (const opal::RenderParameters& f : frames)
  {
    const opal::RenderFrame a = paired.Session.render(f);
    OPAL_CHECK(a.Ran.PairedFields, "unlimited, the fields are held as pairs");
    images.push_back(a.Image);
  }
  for (const bool addressed : { true, false })
  {
    opal::VulkanOptions options;
    options.MemoryLimitBytes = volume.voxelCount() * (8 + 8 + 16 + 8 + 16 + 12) - 1;
    options.Simulated.WithoutBufferDeviceAddress = !addressed;
    opaltest::SceneRenderer single(options);
    single.Session.setVolume(volume);
    bool same = true, layout = true;
    for (std::size_t f = 0; f < frames.size(); ++f)
    {
      const opal::RenderFrame b = single.Session.render(frames[f]);
      same = same && b.Status == opal::FrameStatus::Completed && opaltest::identical(images[f], b.Image);
      layout = layout && b.Ran.PairedFields == !addressed;
    }
    const std::string how = addressed ? " (by address)" : " (a device that cannot address)";
    OPAL_CHECK(layout, "under the limit the fields are held unpaired by address, else paired" + how);
    OPAL_CHECK(same, "the images equal the unlimited paired ones pixel for pixel (above, side, preview, every order)" + how);
    OPAL_CHECK(!addressed ||
        single.Session.context().memoryPeak() + volume.voxelCount() * 20 <= paired.Session.context().memoryPeak(),
      "the device peak falls by 20 bytes a voxel: " + std::to_string(single.Session.context().memoryPeak()) +
        " against " + std::to_string(paired.Session.context().memoryPeak()) + " bytes" + how);
    const auto messages = single.Session.context().validationMessages();
    OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  }
}

// A volume one voxel wide keeps its pairs under a limit below them and when
// addressed (a small simulated range): its reads have no next voxel to take
// the neighbour from. The images equal the unlimited bound session's.
void checkOneVoxelWidePaired(const opal::RenderVolume& volume, const opal::RenderParameters& p)
{
  opaltest::SceneRenderer unlimited(opal::VulkanOptions{});
  const opal::RenderImage reference = unlimited.render(volume, p);
  opal::VulkanOptions tight;
  tight.MemoryLimitBytes = unlimited.Session.context().memoryPeak();
  opal::VulkanOptions addressed;
  addressed.Simulated.MaxStorageBufferRange = 128 << 10; // the fields exceed it, 48 x 36 pixels do not
  for (const opal::VulkanOptions& options : { tight, addressed })
  {
    opaltest::SceneRenderer renderer(options);
    renderer.Session.setVolume(volume);
    const opal::RenderFrame frame = renderer.Session.render(p);
    OPAL_CHECK(frame.Ran.PairedFields && opaltest::identical(frame.Image, reference),
      "a volume one voxel wide is paired and renders the unlimited image (" +
        std::string(options.MemoryLimitBytes ? "under a limit" : "addressed") + ")");
  }
}

// A frame whose Exposure is set measures none, so it holds no pixels for
// the automatic exposure's thumbnail (96 x 72 of a 400 x 300 image, 40 x 30
// of a 40 x 30 one): a region of 2 x 2 pixels takes the same device memory
// whatever the whole image's size.
void checkFixedExposureHoldsNoThumbnail(const opal::RenderVolume& volume, const opal::RenderParameters& view)
{
  std::vector<std::uint64_t> peaks;
  for (const std::array<int, 2> size : { std::array<int, 2>{ 400, 300 }, std::array<int, 2>{ 40, 30 } })
  {
    opal::RenderParameters p = view;
    p.Exposure = 1.0;
    p.ImageSize = size;
    p.ImageRegion = { 10, 10, 2, 2 };
    opaltest::SceneRenderer renderer(opal::VulkanOptions{});
    renderer.Session.setVolume(volume);
    const opal::RenderFrame frame = renderer.Session.render(p);
    OPAL_CHECK(frame.Status == opal::FrameStatus::Completed && !frame.Ran.Exposure,
      "a frame of fixed exposure completes without measuring one");
    peaks.push_back(renderer.Session.context().memoryPeak());
  }
  OPAL_CHECK(peaks[0] == peaks[1], "a 2 x 2 region of fixed exposure holds no thumbnail's pixels: device peak " +
      std::to_string(peaks[0]) + " bytes in a 400 x 300 image, " + std::to_string(peaks[1]) + " in a 40 x 30 one");
}

// The frame ticket (RenderSession::startFrame, what opal-render and the
// filter's background frames use): a frame taken from the session's worker
// equals the frame render() gives on the caller's thread, pixel for pixel; a
// cancelled one is counted abandoned and the session renders on; nothing is
// taken while none has finished.
void checkFrameTicket(opal::RenderSession& session, const opal::RenderParameters& parameters,
  const opal::RenderImage& foreground)
{
  OPAL_CHECK(!session.takeFrame() && session.backgroundState() == opal::BackgroundState::None,
    "nothing to take before a frame starts");
  session.startFrame(opal::resolveFrame(parameters));
  while (session.backgroundState() == opal::BackgroundState::Running)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  OPAL_CHECK(session.backgroundProgress() == 1.0, "a finished frame's progress is 1");
  const std::optional<opal::RenderFrame> background = session.takeFrame();
  OPAL_CHECK(background && background->Status == opal::FrameStatus::Completed &&
      opaltest::identical(background->Image, foreground),
    "a background frame equals the foreground frame pixel for pixel");
  OPAL_CHECK(session.completedBackgroundFrames() == 1, "the taken frame is counted completed");

  opal::RenderParameters lit = parameters;
  lit.LightPosition = { 3.0, 60.0, 2.0 }; // a light pass to cancel in
  session.startFrame(opal::resolveFrame(lit));
  session.cancelFrame();
  OPAL_CHECK(session.backgroundState() == opal::BackgroundState::None &&
      session.completedBackgroundFrames() + session.abandonedBackgroundFrames() == 2,
    "a cancelled frame is gone and counted");
  // The cancelled light pass had overwritten part of the held light field.
  OPAL_CHECK(opaltest::identical(session.render(parameters).Image, foreground),
    "after a cancel in the light pass the session renders the same (the half-written field is not reused)");
  session.startFrame(opal::resolveFrame(lit));
  const opal::RenderFrame over = session.render(parameters); // cancels the running frame first
  OPAL_CHECK(opaltest::identical(over.Image, foreground) && session.backgroundState() == opal::BackgroundState::None,
    "render() takes the session back from a running background frame");
  opal::RenderParameters bad = parameters;
  bad.WavelengthStep = 0;
  bool refused = false;
  try
  {
    session.startFrame(opal::resolveFrame(bad));
  }
  catch (const std::invalid_argument& e)
  {
    refused = std::string(e.what()).find("WavelengthStep") != std::string::npos;
  }
  OPAL_CHECK(refused && session.backgroundState() == opal::BackgroundState::None,
    "a bad frame does not start, naming the parameter");
}

// readRuns and writeRuns through staging buffers (a discrete GPU's path,
// VulkanOptions::StagingTransfers): runs of 150 MB in all, one of 100 MB,
// staged in batches of at most VulkanBuffer::FillRoundBytes (64 MB), each
// byte where it belongs, as the buffer's own rounds (read) read it back.
void checkStagedRuns()
{
  opal::VulkanOptions options;
  options.StagingTransfers = true;
  opal::VulkanContext context(options);
  constexpr std::uint64_t MB = std::uint64_t(1) << 20;
  const std::uint64_t bytes = 160 * MB;
  opal::VulkanBuffer buffer(context, bytes, "staged runs", opal::BufferPlacement::DeviceAddressed); // beyond a range
  OPAL_CHECK(buffer.as<char>() == nullptr, "set-up: the buffer is not mapped (staged)");
  std::vector<char> zeros(bytes, 0);
  buffer.upload(zeros.data(), bytes);
  std::vector<char> host(bytes);
  for (std::uint64_t i = 0; i < bytes; ++i)
  {
    host[i] = static_cast<char>((i * 0x9E3779B97F4A7C15ull) >> 56); // no period of a batch
  }
  const std::vector<opal::WrittenRun> runs{ { &buffer, 0, 100 * MB }, { &buffer, 100 * MB + 16, 3 },
    { &buffer, 120 * MB, 30 * MB } };
  std::vector<const char*> from;
  for (const opal::WrittenRun& run : runs)
  {
    from.push_back(host.data() + run.Begin);
  }
  opal::writeRuns(runs, from);
  std::vector<char> device(bytes);
  buffer.read(bytes, [&](std::uint64_t first, std::uint64_t count, const void* at) {
    std::copy_n(static_cast<const char*>(at), count, device.data() + first);
  });
  std::vector<char> expected(bytes, 0);
  std::vector<opal::ReadRun> readBack;
  std::vector<std::vector<char>> into;
  for (const opal::WrittenRun& run : runs)
  {
    std::copy_n(host.data() + run.Begin, run.Bytes, expected.data() + run.Begin);
    readBack.push_back({ &buffer, run.Begin, run.Bytes });
    into.emplace_back(run.Bytes);
  }
  OPAL_CHECK(device == expected, "writeRuns in batches: each run's bytes written where they belong, no others");
  std::vector<char*> intoAt;
  for (std::vector<char>& run : into)
  {
    intoAt.push_back(run.data());
  }
  opal::readRuns(readBack, intoAt);
  bool same = true;
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    same = same && std::equal(into[r].begin(), into[r].end(), host.begin() + static_cast<std::ptrdiff_t>(runs[r].Begin));
  }
  OPAL_CHECK(same, "readRuns in batches: each run's bytes read back");
}

// A grid of more voxels than the device's 32-bit voxel index holds (2^32:
// 65536 x 65536 x 1) is refused by setVolume, naming the count, before any
// array is read (its arrays here are a voxel long), and the session renders
// its volume as before; a layer y beyond 2^31 - 1 voxels (65536 x 1 x 32768)
// likewise; grids just within both limits pass those checks (their arrays
// absent, validate stops at them).
void checkTooManyVoxels(opal::RenderSession& session, const opal::RenderParameters& view, const opal::RenderImage& image)
{
  const float scattering = 0.0f, distance = 1.0f;
  const std::int32_t domain = -1;
  opal::RenderVolume huge;
  huge.Dimensions = { 65536, 65536, 1 };
  huge.Spacing = { 0.01, 0.01, 0.01 };
  huge.ScatteringCoefficient = &scattering;
  huge.DomainId = &domain;
  huge.SurfaceDistance = &distance;
  std::string message;
  try
  {
    session.setVolume(huge);
  }
  catch (const std::invalid_argument& e)
  {
    message = e.what();
  }
  OPAL_CHECK(message.find("4294967296 voxels") != std::string::npos && message.find("4294967295") != std::string::npos,
    "a grid of 2^32 voxels is refused naming its count and the most (" + message + ")");
  huge.Dimensions = { 65536, 1, 32768 }; // a layer y of 2^31 voxels
  OPAL_CHECK(opal::validate(huge).find("2147483648 voxels each") != std::string::npos,
    "a layer y of 2^31 voxels is refused naming its count (" + opal::validate(huge) + ")");
  huge.ScatteringCoefficient = nullptr; // validate stops at the absent array, reading none
  for (const std::array<int, 3> within : { std::array<int, 3>{ 65536, 65535, 1 }, std::array<int, 3>{ 65535, 1, 32768 } })
  {
    huge.Dimensions = within;
    OPAL_CHECK(opal::validate(huge).find("lacks") != std::string::npos,
      "a grid within both limits passes their checks (" + opal::validate(huge) + ")");
  }
  const opal::RenderFrame frame = session.render(view);
  OPAL_CHECK(frame.Status == opal::FrameStatus::Completed && opaltest::identical(frame.Image, image),
    "after the refusal the session renders its volume as before");
}

// The first frame runs every stage; a camera-only frame reuses the volume
// and the light field, giving exactly a fresh session's image, as a
// render-only build does. Returns that camera's image.
opal::RenderImage checkCameraReuse(opal::RenderSession& session, const opal::ModelParameters& model,
  const opal::BuiltVolume& volume, const opal::RenderParameters& moved)
{
  const opal::RenderFrame a = session.render(smallView());
  OPAL_CHECK(a.Status == opal::FrameStatus::Completed && a.Ran.Upload && a.Ran.LightPass && a.Ran.Readback,
    "the first frame uploads, runs the light pass and completes (" + stages(a.Ran) + ")");
  const opal::RenderFrame b = session.render(moved);
  OPAL_CHECK(b.Status == opal::FrameStatus::Completed && !b.Ran.Upload && !b.Ran.LightPass && b.Ran.March,
    "a camera-only frame reuses the volume and the light field (" + stages(b.Ran) + ")");
  OPAL_CHECK(!opaltest::identical(a.Image, b.Image), "the new camera gives a new image");
  opaltest::SceneRenderer fresh(opal::VulkanOptions{});
  const opal::RenderImage c = fresh.render(volume.renderVolume(), moved);
  OPAL_CHECK(opaltest::identical(b.Image, c), "the reused light field gives exactly a fresh session's image");
  // opal-render's build keeps only what the render reads: the same image.
  const auto renderOnly = opal::buildVolume(model, nullptr, opal::VolumeArrays::Render);
  OPAL_CHECK(renderOnly->VoxelType.empty() && renderOnly->LatticeOrientation.empty() &&
      renderOnly->ScatteringCoefficient == volume.ScatteringCoefficient && renderOnly->DomainId == volume.DomainId &&
      renderOnly->SurfaceDistance == volume.SurfaceDistance,
    "a render-only build keeps the render's fields, equal to the whole build's, and no description");
  OPAL_CHECK(opaltest::identical(b.Image, fresh.render(renderOnly->renderVolume(), moved)),
    "a render-only build renders exactly the whole build's image");
  return b.Image;
}

// What the light field depends on reruns it; an abort during the light pass
// is an explicit status, and the next frame reruns the pass.
void checkLightPassReruns(opal::RenderSession& session, const opal::RenderParameters& moved)
{
  auto lightPassRuns = [&session, &moved](const std::string& what, auto change) {
    opal::RenderParameters p = moved;
    change(p);
    const opal::RenderFrame frame = session.render(p);
    OPAL_CHECK(frame.Ran.LightPass && !frame.Ran.Upload, what + " reruns the light pass (" + stages(frame.Ran) + ")");
    session.render(moved); // back to the reference light
  };
  lightPassRuns("a new light position", [](opal::RenderParameters& p) { p.LightPosition = { 5.0, 60.0, 0.0 }; });
  lightPassRuns("a model rotation", [](opal::RenderParameters& p) { p.ModelRotation = { 5.0, 0.0, 0.0 }; });
  lightPassRuns("a new refractive index", [](opal::RenderParameters& p) { p.RefractiveIndex = 1.4; });
  lightPassRuns("the paper's fall-off rule", [](opal::RenderParameters& p) { p.LightFalloffAtEntry = true; });

  opal::RenderParameters lit = moved;
  lit.LightPosition = { -5.0, 60.0, 0.0 };
  const opal::RenderFrame aborted = session.render(lit, [](double) { return false; });
  OPAL_CHECK(aborted.Status == opal::FrameStatus::Aborted && aborted.Image.RGB.empty(),
    "an abort is reported as FrameStatus::Aborted with no image");
  const opal::RenderFrame after = session.render(lit);
  OPAL_CHECK(after.Status == opal::FrameStatus::Completed && after.Ran.LightPass,
    "after an aborted light pass the next frame runs it (" + stages(after.Ran) + ")");
}

// Fields of 8.5 M voxels (68 MB of ScatteringCoefficient and DomainId, as of
// SurfaceDistance) go up in two rounds of VulkanBuffer::FillRoundBytes; with
// every order in an absorbing body the solve reads its medium back from the
// device's cells and absorption cells (two rounds through staging); fields
// held unpaired; a grid one voxel wide, paired.
void checkLargeFields(opaltest::SceneRenderer& renderer, const opal::ModelParameters& model,
  const opal::RenderParameters& moved)
{
  opal::ModelParameters large = model;
  large.Dimensions = { 256, 128, 260 };
  const auto largeVolume = opal::buildVolume(large);
  checkStagingTransfers(largeVolume->renderVolume(), moved, renderer.render(largeVolume->renderVolume(), moved),
    "fields in two rounds");
  large.BodyAbsorption = 0.05;
  const auto absorbingVolume = opal::buildVolume(large);
  opal::RenderParameters everyOrder = moved;
  everyOrder.ScatteringOrders = opal::ScatteringOrdersKind::All;
  everyOrder.ScatteringPhotons = 2000;
  checkStagingTransfers(absorbingVolume->renderVolume(), everyOrder,
    renderer.render(absorbingVolume->renderVolume(), everyOrder), "every order, its medium read back in two rounds");
  opal::ModelParameters absorbingSmall = model;
  absorbingSmall.Dimensions = { 64, 32, 80 };
  absorbingSmall.BodyAbsorption = 0.05;
  checkUnpairedFields(opal::buildVolume(absorbingSmall)->renderVolume(), moved);
  opal::ModelParameters oneWide = model;
  oneWide.Dimensions = { 1, 200, 500 };
  checkOneVoxelWidePaired(opal::buildVolume(oneWide)->renderVolume(), moved);
}

// What the process's exit does to every live session: a running frame
// stops, the device objects go, and a later use says so.
void checkRelease(opal::RenderSession& session, const opal::RenderParameters& moved)
{
  session.startFrame(opal::resolveFrame(moved));
  session.release();
  bool refused = false;
  try
  {
    session.render(moved);
  }
  catch (const opal::VulkanError& e)
  {
    refused = std::string(e.what()).find("released") != std::string::npos;
  }
  OPAL_CHECK(refused && session.backgroundState() == opal::BackgroundState::None,
    "a released session stops its frame and refuses a render, saying why");
}

int TestOpalRenderSession(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  checkStagedRuns();
  opal::ModelParameters model;
  model.Dimensions = { 40, 20, 50 };
  model.DomainCount = 30;
  const auto volume = opal::buildVolume(model);
  opal::RenderSession& session = renderer->Session;
  session.setVolume(volume->renderVolume());
  // A new camera only: the eye moves and looks at the same point.
  opal::RenderParameters moved = smallView();
  moved.EyePosition = { 8.0, 58.0, 6.0 };
  const opal::RenderImage image = checkCameraReuse(session, model, *volume, moved);
  checkLightPassReruns(session, moved);

  checkScatteredLightStages(session, moved);
  checkSharedSolve(session, volume->renderVolume(), moved);
  checkScatteredLightFromGrid(volume->renderVolume(), moved);
  checkKeptShadowsCounted(volume->renderVolume(), moved);
  checkStagingTransfers(volume->renderVolume(), moved, image);
  checkFixedExposureHoldsNoThumbnail(volume->renderVolume(), moved);
  checkFrameTicket(session, moved, image);
  checkTooManyVoxels(session, moved, image);
  // After the frame ticket (which renders the session's volume).
  checkLargeFields(*renderer, model, moved);

  const auto messages = renderer->context().validationMessages();
  OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  checkRelease(session, moved);
  return opaltest::finish("TestOpalRenderSession");
}
