// The view march shared by processes, each holding a piece of the volume's
// layers z (docs/design.md §8.1), played by sessions on threads: share 0
// starts every ray; each share marches the rays in its piece, reading the
// fields it reads per voxel from buffers of its layers and their halo
// alone, and passes the rays it took up to every share after each round,
// until none goes on; every share then writes every finished ray's pixel.
// Each share's image must be the lone session's, value for value: a ray's
// state crosses between shares bit for bit, as between one process's
// pieces, and no read reaches beyond a share's halo. fig12 lit from above,
// with the spectrum and the exposure's thumbnail (marched shared too), and
// with the edge pixels' sub-rays (the ring's rays, share 0's queues, also
// to a share whose buffers an earlier frame made larger, the sub-rays' sums
// kept between dispatches); fire-opal (an absorbing body,
// coupled-wave fcc planes, energy conservation's rounds and Bragg shadows,
// every order) lit from the side on 3 shares with the sub-rays. In fig12's
// 3-share case and fire-opal's each share holds its piece of the light
// fields (and fire-opal's every-order field) alone (holdPiece), the light
// computed by the shares together (fire-opal's walks to the light going
// between the shares, each reading its piece's medium alone), and a frame
// alone after it computes them whole again. A share aborting in the shares'
// walks to the light stops every share's step, and each frame computes the
// light alone. The same with the light fields bound by piece (a lone
// session's layout), read at an index less the piece's first voxel, which
// must follow the layers held into the march of a frame that computes the
// light alone. A share aborting in its light pass or midway through its
// march stops every share's frame (no hang, no image); bad shares are refused;
// a piece's whole field refused by a memory limit leaves nothing stale.
#include "OpalParallel.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalShareMeeting.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"
#include "OpalVulkanError.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
// What a share's frame gave: the frame, or the message it threw.
struct ShareResult
{
  opal::RenderFrame Frame;
  std::string Failure;
  std::string Validation; // the validation layer's first message, if any
  // With HeldPieces: the layers its light fields held for the shared frame,
  // and its frame alone after it, with the layers they held then.
  std::pair<int, int> HeldLayers;
  bool LightShared = false; // the light computed by the shares together
  opal::RenderFrame Alone;
  std::pair<int, int> HeldAlone;
  // With MediumHeld: the layers its medium held, its device's memory peak
  // through the shared frame, what its frame alone after it was refused with,
  // and whether the whole piece's holding then dropped the volume.
  std::pair<int, int> MediumLayers;
  std::uint64_t SharedPeak = 0;
  std::string AloneRefusal;
  bool VolumeDropped = false;
};

// How the shares run: share 1 stops its frame once its progress passes
// `Share1StopsAt` (above 1: never) and, with `Share1Before`, rendered that
// frame alone first (its buffers then larger); with `Staging`, each share's
// host copies go through staging buffers (a discrete GPU's path:
// VulkanOptions::StagingTransfers); with `HeldPieces` each share holds its
// piece of the light fields alone (holdPiece), computed by the shares
// together (shareLightPass) before the frame, and renders alone after it;
// share 1 then stops that step once its progress passes `Share1StopsLightAt`.
// With `PiecesBound` the fields keep a lone session's layout (bound and
// paired at this size) and the march reads them whole, the light fields
// held by piece read at an index less the piece's first voxel; otherwise
// each share reads its piece's fields alone, by address (MarchPieceFieldsOnly).
// With `MediumHeld` each share holds its piece before its volume is set, so
// that its medium's cells hold the piece alone too; the shares then solve
// every order together as well (solveScatteredLightShared), and a frame
// alone after the shared one is refused, and renders once the volume is set
// again for the whole.
struct SharedRun
{
  double Share1StopsAt = 2.0;
  const opal::RenderParameters* Share1Before = nullptr;
  bool Staging = false;
  bool HeldPieces = false;
  double Share1StopsLightAt = 2.0;
  bool PiecesBound = false;
  bool MediumHeld = false;
};

using Sessions = std::vector<std::unique_ptr<opaltest::SceneRenderer>>;

// `shares` sessions with `run`'s options, under the validation layer.
Sessions makeSessions(const SharedRun& run, int shares)
{
  opal::VulkanOptions options;
  options.Validation = true;
  options.MarchPieceFieldsOnly = !run.PiecesBound;
  options.StagingTransfers = run.Staging;
  Sessions sessions;
  for (int share = 0; share < shares; ++share)
  {
    sessions.push_back(std::make_unique<opaltest::SceneRenderer>(options));
  }
  return sessions;
}

// The sessions the cases keep, each made once, so that its pipelines are
// built once (on lavapipe most of a case's time is its sessions' pipelines):
// the lone session that renders each case's reference image, and the
// shares' sessions of each kind of options (the fields bound, through
// staging). A kept session takes each case's volume and pieces anew, after
// whatever its last case did (an abort, a frame alone, a piece held): a
// session serving many stones in turn, as the live view's does.
struct KeptSessions
{
  std::unique_ptr<opaltest::SceneRenderer> Lone;
  std::map<std::pair<bool, bool>, Sessions> Shares;

  // The first `shares` kept sessions of `run`'s options, made as needed.
  std::vector<opal::RenderSession*> sharesFor(const SharedRun& run, int shares)
  {
    Sessions& kept = this->Shares[{ run.PiecesBound, run.Staging }];
    if (kept.size() < static_cast<std::size_t>(shares))
    {
      Sessions more = makeSessions(run, shares - static_cast<int>(kept.size()));
      std::move(more.begin(), more.end(), std::back_inserter(kept));
    }
    std::vector<opal::RenderSession*> sessions;
    for (int share = 0; share < shares; ++share)
    {
      sessions.push_back(&kept[static_cast<std::size_t>(share)]->Session);
    }
    return sessions;
  }
};

// `session` set up as share `share` of `shares` as `run` says, given
// `stone`, its march shared through `meeting`.
void prepareShare(opal::RenderSession& session, const opal::RenderVolume& stone, int share, int shares,
  const SharedRun& run, opaltest::Meeting& meeting)
{
  session.shareMarch(std::nullopt);
  session.holdPiece(run.MediumHeld ? share : 0, run.MediumHeld ? shares : 1); // a kept session's last piece let go
  session.setVolume(stone);
  if (share == 1 && run.Share1Before)
  {
    session.render(*run.Share1Before);
  }
  if (run.HeldPieces)
  {
    session.holdPiece(share, shares);
  }
  session.shareMarch(opal::RenderSession::MarchShare{ share, shares,
    [&meeting, share](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
      return meeting.meet(share, false, mine, sink);
    } });
}

// Before the shared frame, with HeldPieces: the shares compute the light
// together (whether they did), and with MediumHeld solve every order too.
bool shareLight(opal::RenderSession& session, const opal::RenderParameters& p, int share, int shares,
  const SharedRun& run, opaltest::Meeting& meeting)
{
  const auto meetBytes = [&](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
    return meeting.meet(share, false, mine, sink);
  };
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  const bool shared = session.shareLightPass(
    frame, share, shares,
    [&](const std::optional<std::vector<char>>& mine, const opal::RenderSession::ShareSink& sink) {
      return meeting.meet(share, true, mine, sink);
    },
    meetBytes, [&](double done) { return share != 1 || done < run.Share1StopsLightAt; });
  if (run.MediumHeld && p.ScatteringOrders == opal::ScatteringOrdersKind::All)
  {
    session.solveScatteredLightShared(
      frame, share, shares,
      [&](const std::optional<std::vector<double>>& mine) { return meeting.meetScores(share, mine); }, meetBytes);
  }
  return shared;
}

// After the shared frame, with HeldPieces: the share's frame alone (with
// MediumHeld first refused, then rendered once the volume is set whole).
void renderAloneAfter(
  opal::RenderSession& session, const opal::RenderVolume& stone, const opal::RenderParameters& p, const SharedRun& run,
  ShareResult& result)
{
  session.shareMarch(std::nullopt);
  if (run.MediumHeld)
  {
    try
    {
      session.render(p);
    }
    catch (const std::exception& e)
    {
      result.AloneRefusal = e.what();
    }
    session.holdPiece(0, 1); // the whole: a medium held by piece cannot serve it
    result.VolumeDropped = !session.holdsVolume();
    session.setVolume(stone);
  }
  result.Alone = session.render(p);
  result.HeldAlone = session.heldLightLayers();
}

// Share `share`'s part of the shared frame, as `run` says.
ShareResult renderShare(opal::RenderSession& session, const opal::RenderVolume& stone, const opal::RenderParameters& p,
  int share, int shares, const SharedRun& run, opaltest::Meeting& meeting)
{
  ShareResult result;
  try
  {
    if (run.HeldPieces)
    {
      result.LightShared = shareLight(session, p, share, shares, run, meeting);
    }
    result.Frame = session.render(p, [&](double done) { return share != 1 || done < run.Share1StopsAt; });
    result.HeldLayers = session.heldLightLayers();
    result.MediumLayers = session.heldMediumLayers();
    result.SharedPeak = session.context().memoryPeak();
    if (run.HeldPieces)
    {
      renderAloneAfter(session, stone, p, run, result);
    }
  }
  catch (const std::exception& e)
  {
    result.Failure = e.what();
  }
  const auto messages = session.context().validationMessages();
  result.Validation = messages.empty() ? "" : messages.front();
  return result;
}

// `shares` sessions, each reading its piece's fields alone, render `p` of
// `stone` on as many threads, their march shared, as `run` says: `kept`'s
// sessions where given, but fresh ones where share 1 renders a larger frame
// before (its buffers must be larger than the others') or the medium is held
// by piece (held from the volume's upload; its memory peak compared).
std::vector<ShareResult> sharedFrames(const opal::RenderVolume& stone, const opal::RenderParameters& p, int shares,
  const SharedRun& run, KeptSessions* kept)
{
  opaltest::Meeting meeting(shares);
  Sessions fresh;
  std::vector<opal::RenderSession*> sessions;
  if (kept && !run.Share1Before && !run.MediumHeld)
  {
    sessions = kept->sharesFor(run, shares);
  }
  else
  {
    fresh = makeSessions(run, shares);
    for (const auto& renderer : fresh)
    {
      sessions.push_back(&renderer->Session);
    }
  }
  for (int share = 0; share < shares; ++share)
  {
    prepareShare(*sessions[static_cast<std::size_t>(share)], stone, share, shares, run, meeting);
  }
  std::vector<ShareResult> results(static_cast<std::size_t>(shares));
  std::vector<std::thread> threads;
  for (int share = 0; share < shares; ++share)
  {
    threads.emplace_back([&, share] {
      results[static_cast<std::size_t>(share)] =
        renderShare(*sessions[static_cast<std::size_t>(share)], stone, p, share, shares, run, meeting);
    });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  for (opal::RenderSession* session : sessions)
  {
    session->shareMarch(std::nullopt); // the meeting ends here
  }
  return results;
}

// Share `share` of `shares`' layers of `stone` and `halo` beside them, within
// the grid: what its light fields hold by piece (SweepHaloRows, 2), and its
// medium where held by piece (TraceStepLayers + 2, 6).
std::pair<int, int> heldPiece(const opal::RenderVolume& stone, int share, int shares, int halo = 2)
{
  const int layers = stone.Dimensions[2];
  const std::pair<int, int> piece = opal::evenShare(layers, share, shares);
  return { std::max(piece.first - halo, 0), std::min(piece.second + halo, layers) };
}

// Every share of `shares` renders the lone session's image, value for value.
void checkShared(KeptSessions& kept, const opal::RenderVolume& stone, const opal::RenderParameters& p, int shares,
  const std::string& scene, const SharedRun& run = {})
{
  const opal::RenderImage lone = kept.Lone->render(stone, p);
  const std::vector<ShareResult> results = sharedFrames(stone, p, shares, run, &kept);
  for (std::size_t share = 0; share < results.size(); ++share)
  {
    const ShareResult& result = results[share];
    const std::string what = scene + ", share " + std::to_string(share) + " of " + std::to_string(shares);
    OPAL_CHECK(result.Failure.empty() && result.Frame.Status == opal::FrameStatus::Completed,
      what + ": the frame completes" + (result.Failure.empty() ? "" : " (threw: " + result.Failure + ")"));
    OPAL_CHECK(result.Validation.empty(), what + ": the validation layer is silent " + result.Validation);
    OPAL_CHECK(opaltest::identical(result.Frame.Image, lone), what + ": the lone session's image, value for value");
    const opal::RenderTimings& t = result.Frame.Image.Timings;
    OPAL_CHECK(t.MarchRounds > 0 && t.MarchRounds <= t.March && lone.Timings.MarchRounds == 0,
      what + ": the rounds timed as a part of the march (" + std::to_string(t.MarchRounds) + " of " +
        std::to_string(t.March) + " s), none alone");
    if (run.HeldPieces)
    {
      // Where share 1 stopped the shared light, each frame computed it alone, whole.
      const bool lightShared = run.Share1StopsLightAt > 1.0;
      OPAL_CHECK(result.LightShared == lightShared,
        what + (lightShared ? ": the shares computed the light together" : ": share 1's abort stopped every share's light"));
      const std::pair<int, int> piece =
        lightShared ? heldPiece(stone, static_cast<int>(share), shares) : std::make_pair(0, stone.Dimensions[2]);
      OPAL_CHECK(result.HeldLayers == piece,
        what + ": its light fields held its piece and halo alone, layers " + std::to_string(piece.first) + " to " +
          std::to_string(piece.second) + " (held " + std::to_string(result.HeldLayers.first) + " to " +
          std::to_string(result.HeldLayers.second) + ")");
      // A frame alone after it needs the whole light field: computed again
      // where the shares computed it (by piece), kept where the frame had;
      // with the medium held by piece refused, and computed once the volume
      // is set again for the whole.
      OPAL_CHECK(result.Alone.Status == opal::FrameStatus::Completed &&
          result.Alone.Ran.LightPass == (lightShared || run.MediumHeld) && opaltest::identical(result.Alone.Image, lone) &&
          result.HeldAlone == std::make_pair(0, stone.Dimensions[2]),
        what + ": a frame alone after it holds the whole light field and gives the lone image");
    }
    if (run.MediumHeld)
    {
      const std::pair<int, int> piece = heldPiece(stone, static_cast<int>(share), shares, 6);
      OPAL_CHECK(result.MediumLayers == piece,
        what + ": its medium held its piece and 6 layers beside it alone, layers " + std::to_string(piece.first) +
          " to " + std::to_string(piece.second) + " (held " + std::to_string(result.MediumLayers.first) + " to " +
          std::to_string(result.MediumLayers.second) + ")");
      OPAL_CHECK(result.AloneRefusal.find("A frame marched by one process alone reads the medium anywhere") !=
            std::string::npos &&
          result.VolumeDropped,
        what + ": a frame alone with the medium held by piece is refused, naming why (" + result.AloneRefusal +
          "), and holding the whole drops the volume");
    }
  }
}

// Each share's medium held by piece (MediumHeld) takes the cells', the
// absorption cells' and SurfaceDistance's bytes beyond its piece and halo (20
// per voxel at least: fire-opal absorbs, SurfaceDistance 4 or a pair of 8)
// off its device's peak through the shared frame, against the same shares
// holding the medium whole.
void checkMediumMemory(const opal::RenderVolume& stone, const opal::RenderParameters& p)
{
  const SharedRun whole{ 2.0, nullptr, false, true, 2.0, true };
  SharedRun byPiece = whole;
  byPiece.MediumHeld = true;
  const std::vector<ShareResult> wholes = sharedFrames(stone, p, 3, whole, nullptr); // fresh: their peaks compared
  const std::vector<ShareResult> pieces = sharedFrames(stone, p, 3, byPiece, nullptr);
  const std::uint64_t layerVoxels = static_cast<std::uint64_t>(stone.Dimensions[0]) * stone.Dimensions[1];
  for (int share = 0; share < 3; ++share)
  {
    const ShareResult& w = wholes[static_cast<std::size_t>(share)];
    const ShareResult& h = pieces[static_cast<std::size_t>(share)];
    const std::pair<int, int> held = heldPiece(stone, share, 3, 6);
    const std::uint64_t unheld = layerVoxels * static_cast<std::uint64_t>(stone.Dimensions[2] - (held.second - held.first));
    OPAL_CHECK(w.Failure.empty() && h.Failure.empty() && h.SharedPeak + unheld * 20 <= w.SharedPeak,
      "share " + std::to_string(share) + ": the medium held by piece takes " + std::to_string(unheld * 20) +
        " bytes off the device's peak (" + std::to_string(h.SharedPeak) + " against " + std::to_string(w.SharedPeak) +
        " bytes)");
  }
}

// `stone` as a rank's gather holds it (docs/design.md §8.1): the medium's
// arrays of `layers` alone, with the whole medium's sums added up from two
// ranks' layers (0 to 20, 20 to the last).
opal::RenderVolume mediumOfLayers(const opal::RenderVolume& stone, std::pair<int, int> layers)
{
  opal::RenderVolume v = stone;
  const std::size_t first = stone.layerVoxels() * static_cast<std::size_t>(layers.first);
  v.ScatteringCoefficient += first;
  v.DomainId += first;
  if (v.AbsorptionCoefficient)
  {
    v.AbsorptionCoefficient += first;
    v.AbsorptionExponent += first;
  }
  opal::MediumSums whole = opal::sumMedium(stone, { 0, 20 });
  whole.add(opal::sumMedium(stone, { 20, stone.Dimensions[2] }));
  v.Held = opal::HeldMedium{ layers, whole };
  return v;
}

// A medium held by layers: the layers a piece reads (its cells' and the
// skin's one beside) are enough, one fewer is refused naming both and keeps
// the volume held; the whole's sums added up from the ranks' layers give the
// whole's domain centres; layers beyond the grid are refused.
void checkMediumOfLayers(opal::RenderSession& session, const opal::RenderVolume& stone)
{
  const opal::RenderVolume enough = mediumOfLayers(stone, { 9, 40 }); // share 1 of 3 of 50: 16 to 33, and 7 beside
  OPAL_CHECK(opal::mediumLayersRead(50, 1, 3) == std::make_pair(9, 40), "share 1 of 3 of 50 layers reads layers 9 to 40");
  OPAL_CHECK(enough.domainCentres() == stone.domainCentres() && enough.absorbs() == stone.absorbs() &&
      enough.colouredAbsorptionExponent() == stone.colouredAbsorptionExponent(),
    "the ranks' sums added up give the whole medium's domain centres and absorption");
  const std::string fewer = opaltest::thrown([&] { session.setVolume(mediumOfLayers(stone, { 10, 40 })); });
  OPAL_CHECK(fewer.find("hold layers z 10 to 40") != std::string::npos &&
      fewer.find("reads layers 9 to 40") != std::string::npos && session.holdsVolume() &&
      session.heldMediumLayers() == std::make_pair(10, 39),
    "a medium lacking a layer the piece reads refused, the volume held kept (" + fewer + ")");
  session.setVolume(enough);
  OPAL_CHECK(session.heldMediumLayers() == std::make_pair(10, 39), "a medium of the layers the piece reads uploaded");
  opal::RenderVolume beyond = enough;
  beyond.Held->Layers = { 10, 51 };
  OPAL_CHECK(opal::validate(beyond).find("is not a range of the volume's 50 layers z") != std::string::npos,
    "a medium held beyond the grid's layers refused (" + opal::validate(beyond) + ")");
}

// A session whose medium holds piece 1 of 3 (layers 16 to 33 of 50 and 6
// beside them) refuses, naming why, what would read the medium beyond it: a
// background frame, a light field shared by other shares than its piece's,
// an every-order solve whose slab it lacks. A medium held by layers (checkMediumOfLayers).
// A piece within its layers keeps the volume; one beyond them drops it.
void checkMediumRefusals(const opal::RenderVolume& stone, const opal::RenderParameters& p)
{
  opal::RenderSession session(opal::VulkanOptions{});
  session.holdPiece(1, 3);
  session.setVolume(stone);
  const opal::ResolvedFrame frame = opal::resolveFrame(p);
  const auto ended = [](const std::optional<std::vector<char>>&, const opal::RenderSession::ShareSink&) { return false; };
  const auto round = [](const std::vector<char>&, const opal::RenderSession::ShareSink&) { return false; };
  const auto noScores = [](const std::optional<std::vector<double>>&) {
    return std::optional<std::vector<std::vector<double>>>();
  };
  const std::string background = opaltest::thrown([&] { session.startFrame(frame); });
  const std::string light = opaltest::thrown([&] { session.shareLightPass(frame, 0, 2, ended, round); });
  const std::string solve = opaltest::thrown([&] { session.solveScatteredLightShared(frame, 2, 3, noScores, round); });
  OPAL_CHECK(background.find("A background frame reads the medium anywhere") != std::string::npos &&
      background.find("layers 10 to 39 of its 50") != std::string::npos,
    "a background frame refused, naming the layers held (" + background + ")");
  OPAL_CHECK(light.find("A light field shared by other processes than the march's") != std::string::npos,
    "a light field shared by other shares refused (" + light + ")");
  OPAL_CHECK(solve.find("An every-order solve shared by other processes than the march's") != std::string::npos,
    "a solve whose slab is not held refused (" + solve + ")");
  checkMediumOfLayers(session, stone);
  session.holdPiece(2, 5); // layers 20 to 30 and 6 beside: within 10 to 39
  OPAL_CHECK(session.holdsVolume() && session.heldMediumLayers() == std::make_pair(10, 39),
    "a piece within the medium's layers keeps the volume");
  session.holdPiece(0, 3);
  OPAL_CHECK(!session.holdsVolume(), "a piece beyond the medium's layers drops the volume, to be set again");
}

// A session holding a piece (0 of 3) whose frame alone must make the light
// fields whole, under a device memory limit that holds the piece's frame
// and not the whole field: the allocation refuses it, naming the limit,
// twice, the session holding no layers after (not a table of freed
// buffers that the next frame writes through); the validation layer silent.
void checkWholeFieldRefused(const opal::RenderVolume& stone, const opal::RenderParameters& p)
{
  opal::VulkanOptions options;
  options.Validation = true;
  options.MarchPieceFieldsOnly = true; // read by address, as a held piece is
  std::uint64_t limit = 0;
  {
    opal::RenderSession probe(options);
    probe.setVolume(stone); // its medium whole: a piece set after holds the light fields alone
    probe.holdPiece(0, 3);
    const std::pair<int, int> held = probe.heldLightLayers();
    probe.render(p);
    const std::uint64_t unheld = static_cast<std::uint64_t>(stone.Dimensions[0]) * stone.Dimensions[1] *
      static_cast<std::uint64_t>(stone.Dimensions[2] - (held.second - held.first));
    limit = probe.context().memoryPeak() - unheld * 8 / 2; // half the whole light field's layers beyond the piece
  }
  options.MemoryLimitBytes = limit;
  opal::RenderSession session(options);
  session.setVolume(stone);
  session.holdPiece(0, 3);
  for (int attempt = 1; attempt <= 2; ++attempt)
  {
    std::string message;
    try
    {
      session.render(p);
    }
    catch (const opal::VulkanError& e)
    {
      message = e.what();
    }
    OPAL_CHECK(message.find("vkAllocateMemory refused") != std::string::npos &&
        session.heldLightLayers() == std::make_pair(0, 0),
      "the whole light field refused by the memory limit, attempt " + std::to_string(attempt) +
        ": the allocation says so and no layers are held (" + message + ")");
  }
  const auto messages = session.context().validationMessages();
  OPAL_CHECK(messages.empty(), "the refused fields: the validation layer is silent " +
      (messages.empty() ? std::string() : messages.front()));
}

// The message shareMarch (or with `held`, holdPiece) throws for `share` of
// `shares` (with MarchPieces `pieces`); "" where it accepts it.
std::string refusal(int share, int shares, int pieces, bool held = false)
{
  opal::VulkanOptions options;
  options.MarchPieces = pieces;
  opal::RenderSession session(options);
  try
  {
    if (held)
    {
      session.holdPiece(share, shares);
      return "";
    }
    session.shareMarch(opal::RenderSession::MarchShare{ share, shares,
      [](const std::vector<char>&, const opal::RenderSession::ShareSink&) { return true; } });
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  return "";
}

// fig12 lit from above: each share's light fields held by piece; in nine
// bands through staging; the edge pixels' sub-rays with share 1's buffers larger.
void checkPaperShares(KeptSessions& kept, const opal::RenderVolume& paperStone, const opal::RenderParameters& p)
{
  // Each share holding its piece: each layer's sweep, then its queued walks
  // to the light between the shares, taken up where a share holds the
  // layer they need (each walk's voxel kept with it: the share's queue holds
  // its own), their light stored back in their own voxel's share.
  checkShared(kept, paperStone, p, 3, "fig12, each share's light fields held by piece", { 2.0, nullptr, false, true });
  // Bands: 640 pixels across, a shared band holds 24 rows (2^14 pixels at
  // most, in whole rows of 8), so 200 rows take nine, the last of 8 rows;
  // the whole image's states (~190 MB) would pass lavapipe's storage-buffer
  // range (2^27 bytes). Through staging buffers, as on a discrete GPU.
  opal::RenderParameters wide = p;
  wide.ImageSize = { 640, 200 };
  wide.WriteSpectrum = false;
  checkShared(kept, paperStone, wide, 2, "fig12, 640 x 200 pixels in nine bands, through staging", { 2.0, nullptr, true });
  opal::RenderParameters refined = p;
  refined.PixelSamples = 3;
  // Share 1's edge queues' buffers larger than the others' (a larger frame
  // alone before): share 0's queues still go to it.
  opal::RenderParameters larger = refined;
  larger.ImageSize = { 64, 48 };
  checkShared(kept, paperStone, refined, 3, "fig12, the edge pixels' 3 x 3 sub-rays, share 1's buffers larger", { 2.0, &larger });
}

// fire-opal lit from the side: the light fields held and bound by piece,
// share 1 aborting in the walks to the light; with every order, the medium
// held and bound by piece.
void checkFireShares(KeptSessions& kept, const opal::RenderVolume& fireStone, const opal::RenderParameters& p, double refractiveIndex)
{
  opal::RenderParameters side = opaltest::withPresetHints(p, "fire-opal", refractiveIndex);
  side.LightPosition = { 30.0, 12.0, 4.0 };
  side.ScatteringOrders = opal::ScatteringOrdersKind::All;
  side.ScatteringPhotons = 2000;
  const opal::ResolvedFrame frame = opal::resolveFrame(side);
  OPAL_CHECK(frame.Error.empty() && opal::conservesEnergy(frame.Parameters),
    "set-up: fire-opal's frame conserves energy (rounds and Bragg shadows)");
  side.PixelSamples = 3;
  checkShared(kept, fireStone, side, 3, "fire-opal, lit from the side, every order, the edge pixels' sub-rays, light fields by piece",
    { 2.0, nullptr, false, true });
  // Share 1 aborting in the shares' walks to the light after its first work
  // (of two): every share's step stops, none hangs; each frame then computes
  // the light alone, to the lone image.
  opal::RenderParameters single = opaltest::withPresetHints(p, "fire-opal", refractiveIndex);
  single.LightPosition = side.LightPosition;
  checkShared(kept, fireStone, single, 3, "fire-opal, lit from the side, share 1 aborting in the walks to the light",
    { 2.0, nullptr, false, true, 1e-9 });
  // The light fields held by piece, bound: the shared frame, the frames that
  // compute the light alone after share 1's abort (whole, after the frame's
  // parameter block was written) and the frames alone after them.
  checkShared(kept, fireStone, side, 3, "fire-opal, every order, the light fields bound by piece",
    { 2.0, nullptr, false, true, 2.0, true });
  checkShared(kept, fireStone, single, 3, "fire-opal, the light fields bound by piece, share 1 aborting in the walks to the light",
    { 2.0, nullptr, false, true, 1e-9, true });
  // The medium held by piece too, read by address (each dispatch's reads
  // beyond its piece landing outside its buffers) and bound (read at an
  // index less the piece's first voxel): fire-opal from the side with every
  // order (the walks, the shared solve reading each share's slab).
  checkShared(kept, fireStone, side, 3, "fire-opal, every order, the medium held by piece",
    { 2.0, nullptr, false, true, 2.0, false, true });
  checkShared(kept, fireStone, side, 3, "fire-opal, every order, the medium bound by piece",
    { 2.0, nullptr, false, true, 2.0, true, true });
  checkMediumMemory(fireStone, single);
}

// Share 1 aborting in its light pass (before any round) or midway through
// its march: every share's frame stops, none hangs or throws.
void checkAborts(KeptSessions& kept, const opal::RenderVolume& paperStone, const opal::RenderParameters& p)
{
  for (const double stopsAt : { 0.05, 0.5 })
  {
    for (const ShareResult& result : sharedFrames(paperStone, p, 3, { stopsAt }, &kept))
    {
      OPAL_CHECK(result.Failure.empty() && result.Frame.Status == opal::FrameStatus::Aborted && result.Frame.Image.RGB.empty(),
        "share 1 aborting at " + std::to_string(stopsAt) + ": every share's frame stops without an image" +
          (result.Failure.empty() ? "" : " (threw: " + result.Failure + ")"));
    }
  }
}

void checkRefusals()
{
  OPAL_CHECK(refusal(3, 3, 1).find("Share 3 is not one of the 3 shares") != std::string::npos, "share 3 of 3: refused");
  OPAL_CHECK(refusal(0, 2, 3).find("MarchPieces") != std::string::npos, "a shared march with MarchPieces 3: refused");
  OPAL_CHECK(refusal(0, 1, 3).empty(), "one share of one with MarchPieces 3: the march alone, accepted");
  OPAL_CHECK(refusal(3, 3, 1, true).find("share 3 is not one of the 3 shares") != std::string::npos,
    "holding share 3 of 3: refused");
  OPAL_CHECK(refusal(-1, 0, 1, true).find("is not one of the 0 shares") != std::string::npos, "holding of 0 shares: refused");
  OPAL_CHECK(refusal(0, 2, 3, true).find("MarchPieces") != std::string::npos, "holding a piece with MarchPieces 3: refused");
  OPAL_CHECK(refusal(0, 1, 3, true).empty(), "holding the whole of one share with MarchPieces 3: accepted");
}
} // namespace

int TestOpalSharedMarch(int, char*[])
{
  KeptSessions kept{ opaltest::makeRenderer(), {} };
  if (!kept.Lone)
  {
    return opaltest::noDeviceReturnCode();
  }
  opal::RenderParameters p;
  p.ImageSize = { 40, 30 };
  p.PixelSamples = 1;
  p.WriteSpectrum = true;

  opal::ModelParameters paper; // fig12's optics, lit from above
  paper.Dimensions = { 40, 20, 50 };
  const auto paperVolume = opal::buildVolume(paper);
  const opal::RenderVolume paperStone = paperVolume->renderVolume();
  OPAL_CHECK(opal::resolveFrame(p).Parameters.Exposure <= 0.0, "set-up: the exposure is measured on a thumbnail");
  checkPaperShares(kept, paperStone, p);

  opal::ModelParameters fire;
  OPAL_CHECK(fire.applyPreset(opal::presetIndexByName("fire-opal")), "fire-opal is a preset");
  fire.Dimensions = { 40, 20, 50 };
  const auto fireVolume = opal::buildVolume(fire);
  checkFireShares(kept, fireVolume->renderVolume(), p, fire.RefractiveIndex);
  // The medium held by piece, read by address and bound, fig12 lit from
  // above (the sweep and its queued walks).
  checkShared(kept, paperStone, p, 3, "fig12, the medium held by piece", { 2.0, nullptr, false, true, 2.0, false, true });
  checkMediumRefusals(paperStone, p);
  checkAborts(kept, paperStone, p);
  checkWholeFieldRefused(paperStone, p);
  checkRefusals();
  return opaltest::finish("TestOpalSharedMarch");
}
