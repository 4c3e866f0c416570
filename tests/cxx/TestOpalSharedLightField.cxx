// The light field computed by processes together (docs/design.md §8.1),
// played by three sessions on three threads: each computes a share of the
// layers' rows, and the one that puts every share together renders the image
// a session that computed the field alone renders, value for value.
// fire-opal carries every field a share holds (the light field, its
// absorption's, the Bragg shadows of energy conservation), with the fields
// paired (bound) and one value per voxel (addressed); the shares' bytes
// arrive in small pieces that cut across fields and records; and with each
// share's walks to the light forwarded between pieces of the volume, each
// piece reading its fields alone, every walk finished. Lit from the
// side, each share marches from its voxels; lit from above, obliquely
// enough that a path drifts across rows, each sweeps its rows layer after
// layer and passes its edge rows to the shares beside it after each layer
// (without them a share's edge reads nothing above). A share that fails, or
// aborts midway through the layers, ends every share's exchange: no field
// is held, and the frame computes it alone, to the same image. With fewer
// rows than shares, a share of none takes part all the same. The every-order
// field per voxel, written from the tally grid each session holds, is shared
// likewise, its slabs crossing the exchange's chunks, as are the slabs of the
// medium the sessions' shared solve of that grid reads.
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalShareMeeting.h"
#include "OpalTestHarness.h"
#include "OpalVolumeGeometry.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <array>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace
{
// How a share of the three ends: whole, or share 1 failing (its bytes not
// sent) or aborting when half its layers are done.
enum class Ending
{
  Whole,
  ShareFails,
  ShareAborts,
};

// Which field the shares compute: the light field, or the every-order field
// per voxel from the tally grid each session holds.
enum class Field
{
  Light,
  Scattered,
};

bool needs(const opal::RenderSession& session, Field field, const opal::ResolvedFrame& frame)
{
  return field == Field::Light ? session.needsLightPass(frame) : session.needsScatteredField(frame);
}

// Three sessions compute their shares on three threads; share 0's session
// then renders the frame.
opal::RenderFrame sharedFrame(const opal::RenderVolume& volume, const opal::VulkanOptions& options,
  const opal::ResolvedFrame& frame, Field field, Ending ending, const std::string& what)
{
  constexpr int Shares = 3;
  std::vector<std::unique_ptr<opaltest::SceneRenderer>> sessions;
  std::vector<opal::RenderSession*> shares;
  for (int share = 0; share < Shares; ++share)
  {
    sessions.push_back(std::make_unique<opaltest::SceneRenderer>(options));
    shares.push_back(&sessions.back()->Session);
    shares.back()->setVolume(volume);
  }
  // The every-order field's tally grid, solved by the sessions together (their
  // slabs of the medium crossing the exchange's chunks at 120 x 60 x 120).
  const std::vector<bool> solved = field == Field::Scattered ? opaltest::solveTogether(shares, frame, nullptr)
                                                              : std::vector<bool>(Shares, true);
  for (int share = 0; share < Shares; ++share)
  {
    OPAL_CHECK(solved[static_cast<std::size_t>(share)], what + ": the session holds the tally grid");
    OPAL_CHECK(needs(*shares[static_cast<std::size_t>(share)], field, frame), what + ": a fresh session would compute the field");
  }
  opaltest::Meeting meeting(Shares);
  std::vector<char> held(Shares, 0);
  std::vector<std::exception_ptr> failures(Shares);
  std::vector<std::thread> threads;
  for (int share = 0; share < Shares; ++share)
  {
    threads.emplace_back([&, share] {
      const bool troubled = share == 1;
      try
      {
        const auto last = [&](const std::optional<std::vector<char>>& mine, const opal::RenderSession::ShareSink& sink) {
          const bool fails = troubled && ending == Ending::ShareFails;
          return meeting.meet(share, true, fails ? std::nullopt : mine, sink);
        };
        const auto round = [&](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
          return meeting.meet(share, false, mine, sink);
        };
        opal::RenderSession& session = sessions[static_cast<std::size_t>(share)]->Session;
        held[static_cast<std::size_t>(share)] = field == Field::Light
          ? session.shareLightPass(frame, share, Shares, last, round,
              [&](double done) { return !(troubled && ending == Ending::ShareAborts && done > 0.1); })
          : session.shareScatteredField(frame, share, Shares, last, round);
      }
      catch (...)
      {
        failures[static_cast<std::size_t>(share)] = std::current_exception();
      }
    });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  for (int share = 0; share < Shares; ++share)
  {
    OPAL_CHECK(!failures[static_cast<std::size_t>(share)], what + ": share " + std::to_string(share) + " throws nothing");
    OPAL_CHECK(held[static_cast<std::size_t>(share)] == (ending == Ending::Whole),
      what + ": share " + std::to_string(share) + (ending == Ending::Whole ? " holds" : " does not hold") + " the field");
  }
  opal::RenderSession& first = sessions.front()->Session;
  OPAL_CHECK(needs(first, field, frame) == (ending != Ending::Whole), what + ": the session then holds the field, or not");
  const opal::RenderFrame rendered = first.render(frame);
  const auto messages = first.context().validationMessages();
  OPAL_CHECK(messages.empty(),
    what + ": the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  return rendered;
}

void checkLight(const opal::RenderVolume& stone, opal::RenderParameters p, const std::array<double, 3>& light,
  Ending broken, const std::string& where)
{
  p.LightPosition = light;
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  opaltest::SceneRenderer alone({});
  alone.Session.setVolume(stone);
  const opal::RenderFrame lone = alone.Session.render(frame);
  OPAL_CHECK(lone.Status == opal::FrameStatus::Completed, where + ": a session alone renders the frame");
  opal::VulkanOptions unpaired;
  // Below the paired fields (VoxelCell 8, SurfaceDistance 8, light field 16,
  // absorption cells 8 and their light field 16, the Bragg shadows 12): one value per voxel, by address.
  unpaired.MemoryLimitBytes = stone.voxelCount() * (8 + 8 + 16 + 8 + 16 + 12) - 1;
  // A discrete GPU's path: the shares read and written through staging buffers.
  opal::VulkanOptions staged;
  staged.StagingTransfers = true;
  // Each share's walks to the light forwarded through 3 pieces, each piece
  // reading its fields alone (docs/design.md §8.1), every walk finished.
  opal::VulkanOptions forwarded;
  forwarded.MarchPieces = 3;
  forwarded.MarchPieceFieldsOnly = true;
  const std::pair<opal::VulkanOptions, std::string> layouts[] = { { {}, "paired" }, { unpaired, "unpaired" },
    { staged, "paired, staged" }, { forwarded, "unpaired, forwarded" } };
  for (const auto& [options, how] : layouts)
  {
    const opal::RenderFrame shared = sharedFrame(stone, options, frame, Field::Light, Ending::Whole, where + ", " + how);
    OPAL_CHECK(shared.Status == opal::FrameStatus::Completed && shared.Ran.LightPass && opaltest::identical(shared.Image, lone.Image),
      where + ", " + how + ": the shares' field gives the image of a session that computed it alone, value for value");
    OPAL_CHECK(shared.Ran.PairedFields == (how.rfind("unpaired", 0) != 0), where + ", " + how + ": the fields are held " + how);
  }
  const opal::RenderFrame partial = sharedFrame(stone, {}, frame, Field::Light, broken, where + ", a share stopping");
  OPAL_CHECK(partial.Ran.LightPass && opaltest::identical(partial.Image, lone.Image),
    where + ", a share stopping: the frame computes the light alone, to the same image");
}
} // namespace

int TestOpalSharedLightField(int, char*[])
{
  if (!opaltest::makeRenderer())
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
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  OPAL_CHECK(frame.Error.empty() && opal::conservesEnergy(frame.Parameters) && stone.absorbs(),
    "set-up: an absorbing body with energy conservation's Bragg shadows");
  const opal::VolumeGeometry geometry(stone, false);
  const std::array<double, 3> side{ 30.0, 12.0, 4.0 }, above{ 4.0, 60.0, 12.0 };
  OPAL_CHECK(!geometry.lightAboveGrid({ side[0], side[1], side[2] }) && geometry.lightAboveGrid({ above[0], above[1], above[2] }),
    "set-up: one light marched from every voxel, one swept from above");
  checkLight(stone, p, side, Ending::ShareFails, "lit from the side");
  checkLight(stone, p, above, Ending::ShareAborts, "lit from above");

  // Fewer rows than shares: share 0 holds none, sweeps nothing and still
  // takes part in every layer's round.
  model.Dimensions = { 40, 20, 2 };
  const auto thinVolume = opal::buildVolume(model);
  const opal::RenderVolume thin = thinVolume->renderVolume(); // a view of thinVolume's arrays
  opaltest::SceneRenderer alone({});
  alone.Session.setVolume(thin);
  p.LightPosition = above;
  const opal::ResolvedFrame thinFrame = opal::resolveFrame(p);
  const opal::RenderFrame lone = alone.Session.render(thinFrame);
  const opal::RenderFrame shared = sharedFrame(thin, {}, thinFrame, Field::Light, Ending::Whole, "two rows, three shares");
  OPAL_CHECK(lone.Status == opal::FrameStatus::Completed && shared.Ran.LightPass && opaltest::identical(shared.Image, lone.Image),
    "two rows, three shares: the shares' field gives the lone session's image, value for value");

  // The every-order field per voxel, written from the tally grid each
  // session holds: 120 x 60 x 120 voxels, so that a share's slab (288 000
  // voxels, 4.6 MB) crosses two of the exchange's 4 MiB chunks.
  model.Dimensions = { 120, 60, 120 };
  const auto wideVolume = opal::buildVolume(model);
  const opal::RenderVolume wide = wideVolume->renderVolume(); // a view of wideVolume's arrays
  opal::RenderParameters everyOrder = p;
  everyOrder.ScatteringOrders = opal::ScatteringOrdersKind::All;
  everyOrder.ScatteringPhotons = 2000;
  const opal::ResolvedFrame everyFrame = opal::resolveFrame(everyOrder);
  opaltest::SceneRenderer wideAlone({});
  wideAlone.Session.setVolume(wide);
  const opal::RenderFrame wideLone = wideAlone.Session.render(everyFrame);
  OPAL_CHECK(wideLone.Status == opal::FrameStatus::Completed && !wideLone.Ran.ScatteredLightFromGrid,
    "every order: a session alone renders the frame, reading the field per voxel");
  for (const Ending ending : { Ending::Whole, Ending::ShareFails })
  {
    const std::string what = ending == Ending::Whole ? "every order" : "every order, a share failing";
    const opal::RenderFrame shared = sharedFrame(wide, {}, everyFrame, Field::Scattered, ending, what);
    OPAL_CHECK(shared.Status == opal::FrameStatus::Completed && opaltest::identical(shared.Image, wideLone.Image),
      what + ": the shares' field (or, a share failing, the frame's own) gives the lone session's image");
  }
  return opaltest::finish("TestOpalSharedLightField");
}
