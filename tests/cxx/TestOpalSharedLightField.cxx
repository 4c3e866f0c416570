// The light field marched per voxel by processes together (docs/design.md
// §8.1), played in one process: three sessions each march a share of the
// voxels' rows, and the one that puts every share together renders the image
// a session that marched alone renders, value for value. fire-opal lit from
// the side carries every field a share holds (the light field, its
// absorption's, the Bragg shadows of energy conservation), and the shares'
// bytes arrive in small pieces that cut across fields and records, with the
// fields paired (bound) and one value per voxel (addressed). A share whose
// exchange is not whole leaves no light field held: the frame marches alone,
// to the same image. A light above the grid is not marched per voxel.
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace
{
bool identical(const opal::RenderImage& a, const opal::RenderImage& b)
{
  return a.RGB == b.RGB && a.XYZ == b.XYZ && a.Radiance == b.Radiance &&
    a.DominantBraggWavelength == b.DominantBraggWavelength && a.Depth == b.Depth && a.Exposure == b.Exposure;
}

// Hands `bytes` (share `share`'s) to `sink` in pieces of `piece` bytes.
void inPieces(const opal::RenderSession::ShareSink& sink, int share, const std::vector<char>& bytes, std::size_t piece)
{
  for (std::size_t first = 0; first < bytes.size(); first += piece)
  {
    sink(share, first, std::min(piece, bytes.size() - first), bytes.data() + first);
  }
}

// Shares 1 and 2 march and keep their bytes (their exchange not whole);
// share 0 marches last and, where `whole`, is handed theirs. The image share
// 0's session then renders.
opal::RenderFrame sharedFrame(const opal::RenderVolume& volume, const opal::VulkanOptions& options,
  const opal::ResolvedFrame& frame, bool whole, const std::string& what)
{
  std::vector<std::vector<char>> shares(3);
  std::vector<std::unique_ptr<opaltest::SceneRenderer>> sessions;
  for (int share : { 1, 2, 0 })
  {
    sessions.push_back(std::make_unique<opaltest::SceneRenderer>(options));
    opal::RenderSession& session = sessions.back()->Session;
    session.setVolume(volume);
    OPAL_CHECK(session.needsLightMarch(frame), what + ": a fresh session would march the light per voxel");
    const bool marched = session.marchLightFieldShared(frame, share, 3,
      [&](const std::optional<std::vector<char>>& mine, const opal::RenderSession::ShareSink& sink) {
        shares[static_cast<std::size_t>(share)] = *mine;
        if (share != 0 || !whole)
        {
          return false;
        }
        inPieces(sink, 1, shares[1], 1000); // not a multiple of any record's bytes
        inPieces(sink, 2, shares[2], shares[2].size());
        return true;
      });
    OPAL_CHECK(marched == (share == 0 && whole), what + ": share " + std::to_string(share) + " holds the field");
  }
  opal::RenderSession& last = sessions.back()->Session;
  OPAL_CHECK(last.needsLightMarch(frame) == !whole, what + ": the session then holds the light field, or not");
  const opal::RenderFrame rendered = last.render(frame);
  const auto messages = last.context().validationMessages();
  OPAL_CHECK(messages.empty(),
    what + ": the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  return rendered;
}
} // namespace

int TestOpalSharedLightField(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  opal::ModelParameters model;
  OPAL_CHECK(model.applyPreset(opal::presetIndexByName("fire-opal")), "fire-opal is a preset");
  model.Dimensions = { 40, 20, 50 };
  const auto volume = opal::buildVolume(model);
  const opal::RenderVolume stone = volume->renderVolume();
  opal::RenderParameters p;
  p.ImageSize = { 48, 36 };
  p.ScatteringOrders = opal::ScatteringOrdersKind::Single;
  const opal::VolumeRenderHints hints = opal::renderHints(opal::presetIndexByName("fire-opal"), model.RefractiveIndex);
  p.BraggModel = hints.BraggModel.value_or(p.BraggModel);
  p.LatticePlanes = hints.LatticePlanes.value_or(p.LatticePlanes);
  p.LightPosition = { 30.0, 12.0, 4.0 }; // low to the side: the per-voxel march
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  OPAL_CHECK(frame.Error.empty() && opal::conservesEnergy(frame.Parameters) && stone.absorbs(),
    "set-up: an absorbing body with energy conservation's Bragg shadows");

  renderer->Session.setVolume(stone);
  const opal::RenderFrame alone = renderer->Session.render(frame);
  OPAL_CHECK(alone.Status == opal::FrameStatus::Completed, "a session alone renders the frame");
  opal::VulkanOptions unpaired;
  // Below the paired fields (VoxelCell 8, SurfaceDistance 8, light field 16,
  // absorption cells 8 and their light field 16, the Bragg shadows 12): one value per voxel, by address.
  unpaired.MemoryLimitBytes = stone.voxelCount() * (8 + 8 + 16 + 8 + 16 + 12) - 1;
  const std::pair<opal::VulkanOptions, std::string> layouts[] = { { {}, "paired" }, { unpaired, "unpaired" } };
  for (const auto& [options, how] : layouts)
  {
    const opal::RenderFrame shared = sharedFrame(stone, options, frame, true, how);
    OPAL_CHECK(
      shared.Status == opal::FrameStatus::Completed && shared.Ran.LightPass && identical(shared.Image, alone.Image),
      how + ": the shares' field gives the image of a session that marched alone, value for value");
    OPAL_CHECK(shared.Ran.PairedFields == (how == "paired"), how + ": the fields are held " + how);
  }
  const opal::RenderFrame partial = sharedFrame(stone, {}, frame, false, "a share missing");
  OPAL_CHECK(partial.Ran.LightPass && identical(partial.Image, alone.Image),
    "a share missing: the frame marches the light alone, to the same image");

  opal::RenderParameters above = p;
  above.LightPosition = { 0.0, 60.0, 0.0 };
  OPAL_CHECK(!renderer->Session.needsLightMarch(opal::resolveFrame(above)),
    "a light above the grid is swept layer after layer, not marched per voxel");
  return opaltest::finish("TestOpalSharedLightField");
}
