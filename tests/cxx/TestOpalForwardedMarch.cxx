// The view march's rays and the light pass's walks to the light forwarded
// between pieces of the volume (docs/design.md §8.1), in one process: each
// dispatch walks only one slab of layers z, a ray or walk leaving it is saved
// and taken up by the dispatch of the slab it enters. The data-parallel
// render is to forward them so between ranks. Each piece's dispatch reads
// the fields it reads per voxel from buffers holding only its layers and
// their halo (the march: one layer; the walks to the light: five of the
// cells; SurfaceDistance, which the traces read, six), addressed from their
// first layer, as a rank holding only its piece will; the walks write their
// light there too, each at its voxel in the piece that holds it. The forwarded render
// must give the image of the one never forwarded, value for value: every
// state a ray or walk carries across a face (a ray's walk and round, its
// recorded crossings, its sums on the nodes and bins, its pixel's sums; a
// walk's trace, cell walk, optical depths and Bragg shadow) comes back bit
// for bit, and no read reaches beyond the halo, or a value differs. The
// walks to the light are forwarded too: every voxel's where the light is
// low or to the side, the skin voxels' the sweep from above queues; the
// sweep runs piece by piece, each with its piece's fields and two rows.
// fig12's optics and pinfire's grains lit from above; fire-opal (an
// absorbing body, coupled-wave fcc planes, energy conservation's rounds and
// Bragg shadows, every order) lit from the side, and from the front and low
// (its walks to the light along z), and on a grid eight times finer in z
// than across; with the edge pixels' sub-rays (their
// sums kept between dispatches) and the spectrum; fire-opal (whose ray
// carries the most) in 2, 3 and 7 pieces, also with its fields read by
// address and through staging buffers, and whole and bound (paired); more
// pieces than layers (pieces of none); ray states beyond the storage-buffer
// range, refused; pieces' fields alone on a device that cannot address
// buffers, refused; and a schedule of too few sweeps, whose states left
// unfinished refuse the frame rather than give a partial image.
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include <array>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

namespace
{
// A session's options for a march through `pieces` pieces, under the
// validation layer (its synchronization checks included: a ray state read
// before its write is a message); with `piecesOnly`, each piece's dispatch
// reads the fields it reads per voxel from buffers of its layers and their
// halo alone.
opal::VulkanOptions forwardedOptions(int pieces, bool piecesOnly, opal::VulkanOptions options = {})
{
  options.Validation = true;
  options.MarchPieces = pieces;
  options.MarchPieceFieldsOnly = piecesOnly;
  return options;
}

// The sessions the scenes keep, each made once, so that its pipelines are
// built once (on lavapipe most of a scene's time is its sessions'
// pipelines): the unforwarded one, and one per count of pieces and layout,
// each taking every scene's volume in turn.
struct KeptRenderers
{
  opaltest::SceneRenderer Whole{ opal::VulkanOptions{} };
  std::map<std::pair<int, bool>, std::unique_ptr<opaltest::SceneRenderer>> Forwarded;

  // The image through `pieces` pieces (forwardedOptions).
  opal::RenderImage forwarded(const opal::RenderVolume& stone, const opal::RenderParameters& p, int pieces,
    bool piecesOnly = true)
  {
    std::unique_ptr<opaltest::SceneRenderer>& renderer = this->Forwarded[{ pieces, piecesOnly }];
    if (!renderer)
    {
      renderer = std::make_unique<opaltest::SceneRenderer>(forwardedOptions(pieces, piecesOnly));
    }
    return renderer->render(stone, p);
  }
};

// With `bound`, also forwarded through the first count of pieces with the
// fields whole and bound, paired (the layout without piecesOnly).
void checkForwarded(KeptRenderers& kept, const opal::ModelParameters& model, const opal::RenderParameters& p,
  const std::string& scene, std::initializer_list<int> pieceCounts, bool bound = false)
{
  const auto volume = opal::buildVolume(model);
  const opal::RenderVolume stone = volume->renderVolume();
  const opal::RenderImage expected = kept.Whole.render(stone, p);
  for (const int pieces : pieceCounts)
  {
    OPAL_CHECK(opaltest::identical(kept.forwarded(stone, p, pieces), expected),
      scene + ": forwarded through " + std::to_string(pieces) +
        " pieces gives the unforwarded image, value for value");
  }
  if (bound)
  {
    OPAL_CHECK(opaltest::identical(kept.forwarded(stone, p, *pieceCounts.begin(), false), expected),
      scene + ": forwarded with its fields whole and bound, the unforwarded image");
  }
}

// The messages of two frames `p` of `stone` through 3 pieces, one after the
// other in one session, its march in `marchSweeps` sweeps and its walks to
// the light in `lightSweeps` (0: their own); "" for a frame that completes.
std::array<std::string, 2> shortSchedule(
  const opal::RenderVolume& stone, const opal::RenderParameters& p, int marchSweeps, int lightSweeps)
{
  opal::VulkanOptions options;
  options.MarchPieces = 3;
  options.ForwardedMarchSweeps = marchSweeps;
  options.ForwardedLightSweeps = lightSweeps;
  opaltest::SceneRenderer renderer(options);
  renderer.Session.setVolume(stone);
  std::array<std::string, 2> messages;
  for (std::string& message : messages)
  {
    try
    {
      renderer.Session.render(p);
    }
    catch (const std::runtime_error& e)
    {
      message = e.what();
    }
  }
  return messages;
}

// fire-opal lit from the side with every order, and from the front and low
// (its walks along z), also on a grid eight times finer in z.
void checkFireLights(KeptRenderers& kept, opal::ModelParameters fire, const opal::RenderParameters& p)
{
  opal::RenderParameters side = opaltest::withPresetHints(p, "fire-opal", fire.RefractiveIndex);
  side.LightPosition = { 30.0, 12.0, 4.0 };
  side.ScatteringOrders = opal::ScatteringOrdersKind::All;
  side.ScatteringPhotons = 2000;
  const opal::ResolvedFrame frame = opal::resolveFrame(side);
  OPAL_CHECK(frame.Error.empty() && opal::conservesEnergy(frame.Parameters),
    "set-up: fire-opal's frame conserves energy (rounds and Bragg shadows)");
  checkForwarded(kept, fire, side, "fire-opal, lit from the side, every order", { 2, 3, 7 }, true);

  // Lit from the front and low, a light whose walks all cross the pieces along z.
  opal::RenderParameters front = side;
  front.ScatteringOrders = opal::ScatteringOrdersKind::Single;
  front.LightPosition = { 1.0, 4.0, -30.0 };
  checkForwarded(kept, fire, front, "fire-opal, lit from the front (its walks to the light along z)", { 3, 7 });

  // A grid eight times finer in z than across, lit from the side: the
  // traces' steps and the halos count layers, not millimetres.
  opal::ModelParameters fine = fire;
  fine.Dimensions = { 20, 10, 80 };
  fine.PhysicalSize = { 4.0, 2.0, 2.0 };
  front.LightPosition = side.LightPosition;
  checkForwarded(kept, fine, front, "fire-opal on a grid eight times finer in z, lit from the side", { 3, 7 });
}

// The unforwarded march with its fields read by address, one value per
// voxel (below the paired fields' bytes: VoxelCell 8, SurfaceDistance 8,
// light field 16, absorption cells 8 and their light field 16, the Bragg
// shadows 12), against the forwarded one with its pixels read back through
// staging buffers, at a larger grid and single scattering.
void checkAddressedFields(opal::ModelParameters fire, const opal::RenderParameters& p)
{
  opal::RenderParameters side = opaltest::withPresetHints(p, "fire-opal", fire.RefractiveIndex);
  side.LightPosition = { 30.0, 12.0, 4.0 };
  fire.Dimensions = { 80, 40, 100 }; // the ray states (2 MB at 40 x 30 pixels) within the limit
  const auto fireVolume = opal::buildVolume(fire);
  const opal::RenderVolume fireStone = fireVolume->renderVolume();
  opal::VulkanOptions addressed;
  addressed.MemoryLimitBytes = fireStone.voxelCount() * (8 + 8 + 16 + 8 + 16 + 12) - 1;
  addressed.StagingTransfers = true;
  opaltest::SceneRenderer unforwarded(addressed);
  unforwarded.Session.setVolume(fireStone);
  const opal::RenderFrame byAddress = unforwarded.Session.render(side);
  OPAL_CHECK(byAddress.Status == opal::FrameStatus::Completed && !byAddress.Ran.PairedFields,
    "set-up: fire-opal's fields held one value per voxel, by address");
  opal::VulkanOptions staged; // each piece's fields alone are read by address at any memory limit
  staged.StagingTransfers = true;
  opaltest::SceneRenderer forwarded(forwardedOptions(3, true, staged));
  OPAL_CHECK(opaltest::identical(forwarded.render(fireStone, side), byAddress.Image),
    "fire-opal, its fields by address and through staging: forwarded through 3 pieces, each "
    "reading its fields alone, gives the unforwarded image");
}

// Too few sweeps for the paths (two of fig12's march's or walks' to the
// light, lit from above or from the side, where three suffice): the states
// left unfinished after the last pass refuse the frame, naming the pass,
// where an image would lack them; the light field of a refused pass is not
// kept for the next frame. Three sweeps of each leave none.
void checkShortSchedules(const opal::RenderVolume& paperStone, const opal::RenderParameters& p)
{
  const auto marchLeft = shortSchedule(paperStone, p, 2, 0);
  OPAL_CHECK(marchLeft[0].find("The view march forwarded through 3 pieces left ") == 0 &&
      marchLeft[0].find("states unfinished") != std::string::npos,
    "the march in two sweeps: the frame refused, naming the march (got: " + marchLeft[0] + ")");
  const auto lightLeft = shortSchedule(paperStone, p, 0, 2);
  OPAL_CHECK(lightLeft[0].find("The light pass forwarded through 3 pieces left ") == 0 && lightLeft[1] == lightLeft[0],
    "the walks to the light in two sweeps: each frame refused, naming the light pass, no field kept "
    "from the first (got: " + lightLeft[0] + " | " + lightLeft[1] + ")");
  opal::RenderParameters sideLit = p;
  sideLit.LightPosition = { 30.0, 6.0, 4.0 }; // every voxel walks to the light
  const auto sideLeft = shortSchedule(paperStone, sideLit, 0, 2);
  OPAL_CHECK(sideLeft[0].find("The light pass forwarded through 3 pieces left ") == 0,
    "every voxel's walk to the light in two sweeps: the frame refused (got: " + sideLeft[0] + ")");
  const auto enough = shortSchedule(paperStone, p, 3, 3);
  OPAL_CHECK(enough[0].empty() && enough[1].empty(),
    "three sweeps of each: no state left, both frames complete (got: " + enough[0] + " | " + enough[1] + ")");
}

// Ray states beyond the device's storage-buffer range: the frame refused
// before any pass, naming the range, and the session renders the next frame.
// Each piece's fields alone are read by address: a device that cannot
// address buffers is refused up front, naming what it lacks.
void checkDeviceRefusals(const opal::RenderVolume& thin, const opal::RenderParameters& p)
{
  opal::VulkanOptions smallRange;
  smallRange.MarchPieces = 2;
  smallRange.Simulated.MaxStorageBufferRange = 1 << 20; // the fields fit; 40 x 30 pixels' states (2 MB) do not
  opaltest::SceneRenderer limited(smallRange);
  limited.Session.setVolume(thin);
  std::string message = opaltest::thrown([&] { limited.Session.render(p); });
  OPAL_CHECK(message.find("ray states") != std::string::npos && message.find("maxStorageBufferRange of 1048576") != std::string::npos,
    "ray states beyond the storage-buffer range: the frame refused, naming the range (got: " + message + ")");
  opal::RenderParameters small = p;
  small.ImageSize = { 8, 6 };
  OPAL_CHECK(limited.Session.render(small).Status == opal::FrameStatus::Completed,
    "after the refusal, a frame whose ray states fit completes");

  opal::VulkanOptions unaddressable;
  unaddressable.MarchPieces = 2;
  unaddressable.MarchPieceFieldsOnly = true;
  unaddressable.Simulated.WithoutBufferDeviceAddress = true;
  message = opaltest::thrown([&] { opaltest::SceneRenderer refused(unaddressable); });
  OPAL_CHECK(message.find("MarchPieceFieldsOnly") != std::string::npos && message.find("bufferDeviceAddress") != std::string::npos,
    "pieces' fields alone on a device that cannot address buffers: refused, naming both (got: " + message + ")");
}
} // namespace

int TestOpalForwardedMarch(int, char*[])
{
  if (!opaltest::makeRenderer())
  {
    return opaltest::noDeviceReturnCode();
  }
  opal::RenderParameters p;
  p.ImageSize = { 40, 30 };
  p.PixelSamples = 3; // the edge pixels' sub-rays, their sums kept between dispatches
  p.WriteSpectrum = true;

  opal::ModelParameters paper; // fig12's optics
  paper.Dimensions = { 40, 20, 50 };
  KeptRenderers kept;
  checkForwarded(kept, paper, p, "fig12", { 3 });

  opal::ModelParameters grains;
  OPAL_CHECK(grains.applyPreset(opal::presetIndexByName("pinfire")), "pinfire is a preset");
  grains.Dimensions = { 40, 20, 50 };
  checkForwarded(kept, grains, opaltest::withPresetHints(p, "pinfire", grains.RefractiveIndex), "pinfire", { 2 });

  opal::ModelParameters fire;
  OPAL_CHECK(fire.applyPreset(opal::presetIndexByName("fire-opal")), "fire-opal is a preset");
  fire.Dimensions = { 40, 20, 50 };
  checkFireLights(kept, fire, p);
  checkAddressedFields(fire, p);

  const auto paperVolume = opal::buildVolume(paper);
  checkShortSchedules(paperVolume->renderVolume(), p);

  // Three layers in seven pieces: four pieces of none, walked by no ray.
  paper.Dimensions = { 40, 20, 3 };
  const auto thinVolume = opal::buildVolume(paper);
  const opal::RenderVolume thin = thinVolume->renderVolume();
  OPAL_CHECK(opaltest::identical(kept.forwarded(thin, p, 7), kept.Whole.render(thin, p)),
    "three layers in seven pieces: the forwarded render gives the unforwarded image");
  checkDeviceRefusals(thin, p);
  return opaltest::finish("TestOpalForwardedMarch");
}
