// The view march shared by processes, each holding a piece of the volume's
// layers z (docs/design.md §8.1): the rays forwarded between the pieces as
// between one process's (OpalForwardedMarch.cxx), each round of every piece
// at once, the rays each share took up passed to every share between rounds.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

RenderSession::MarchRounds::MarchRounds(const MarchShare& share)
  : Share(share)
{
}

void RenderSession::MarchRounds::begin(std::uint64_t slots)
{
  this->Held.assign(slots * this->Words, gpu::KeptDone);
  this->Fresh.clear();
  this->Live.clear();
  this->DeviceHolds = false;
}

std::vector<std::uint32_t> RenderSession::MarchRounds::liveIn(std::pair<int, int> layers) const
{
  std::vector<std::uint32_t> slots;
  for (const std::uint32_t slot : this->Live)
  {
    const std::uint32_t layer = this->Held[slot * this->Words];
    if (static_cast<int>(layer) >= layers.first && static_cast<int>(layer) < layers.second)
    {
      slots.push_back(slot);
    }
  }
  return slots;
}

void RenderSession::MarchRounds::live(const std::vector<std::uint32_t>& posted)
{
  std::vector<std::uint32_t> slots = this->Live;
  slots.insert(slots.end(), posted.begin(), posted.end());
  slots.insert(slots.end(), this->Posted.begin(), this->Posted.end());
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  this->Live.clear();
  for (const std::uint32_t slot : slots)
  {
    if (this->Held[slot * this->Words] < gpu::KeptUnwritten)
    {
      this->Live.push_back(slot);
    }
  }
  this->Posted.clear();
}

bool RenderSession::MarchRounds::exchange(const std::vector<std::uint32_t>& post, const Received& received)
{
  std::vector<char> bytes(post.size() * sizeof(std::uint32_t));
  std::memcpy(bytes.data(), post.data(), bytes.size());
  return this->exchangeBytes(bytes, received);
}

bool RenderSession::MarchRounds::exchangeBytes(const std::vector<char>& post, const Received& received)
{
  const auto start = Clock::now();
  std::uint32_t mine = 0; // whether this share goes on
  if (!post.empty())
  {
    std::memcpy(&mine, post.data(), std::min(post.size(), sizeof(mine)));
  }
  // Each share's post as words, as it arrives (its bytes counted apart).
  std::vector<std::vector<std::uint32_t>> posts(static_cast<std::size_t>(this->Share.Shares));
  std::vector<std::uint64_t> sizes(posts.size(), 0);
  const auto sink = [&](int share, std::uint64_t first, std::uint64_t count, const char* from) {
    if (share >= 0 && share < this->Share.Shares)
    {
      const auto at = static_cast<std::size_t>(share);
      sizes[at] = std::max(sizes[at], first + count);
      posts[at].resize(std::max<std::size_t>(posts[at].size(), (sizes[at] + 3) / sizeof(std::uint32_t)));
      std::memcpy(reinterpret_cast<char*>(posts[at].data()) + first, from, count);
    }
  };
  this->Ended = true; // a throw ends it too
  this->ExchangeEnded = !this->Share.Round(post, sink);
  bool goesOn = !this->ExchangeEnded && mine != 0;
  int malformed = -1;
  for (int share = 0; share < this->Share.Shares && goesOn; ++share)
  {
    const auto at = static_cast<std::size_t>(share);
    const std::vector<std::uint32_t>& words = posts[at];
    if (share == this->Share.Share)
    {
      continue;
    }
    goesOn = sizes[at] % sizeof(std::uint32_t) == 0 && !words.empty() && words[0] != 0;
    if (goesOn && received && !received(share, words.data() + 1, words.size() - 1))
    {
      malformed = share;
    }
  }
  // The others went on: this share says it stops in its next round (stop).
  this->Ended = !goesOn;
  this->Seconds += secondsSince(start);
  if (malformed >= 0)
  {
    throw std::runtime_error("Share " + std::to_string(malformed) +
      " posted to a shared pass's round what the round does not hold; no image is given.");
  }
  return goesOn;
}

bool RenderSession::MarchRounds::exchangeRays(const std::vector<char>& post)
{
  this->Posted.clear();
  return this->exchangeBytes(post, [this](int, const std::uint32_t* rays, std::uint64_t count) {
    return this->takeRays(rays, count);
  });
}

void RenderSession::MarchRounds::stop()
{
  if (!this->Ended)
  {
    try
    {
      this->exchange({ 0 });
    }
    catch (...)
    {
      // The failure that left the rounds is the one to report.
    }
  }
}

// Another share's rays (each its slot and state) written into Held, their
// slots the device's ray states now lack (Fresh).
bool RenderSession::MarchRounds::takeRays(const std::uint32_t* rays, std::uint64_t count)
{
  const std::uint64_t record = 1 + this->Words, slots = this->Held.size() / this->Words;
  if (count % record != 0)
  {
    return false;
  }
  for (std::uint64_t at = 0; at < count; at += record)
  {
    if (rays[at] >= slots)
    {
      return false;
    }
    std::copy_n(rays + at + 1, this->Words, this->Held.begin() + static_cast<std::ptrdiff_t>(rays[at] * this->Words));
    this->Fresh.push_back(rays[at]);
    this->Posted.push_back(rays[at]);
  }
  return true;
}

RenderSession::FrameRounds::FrameRounds(RenderSession& session)
  : Session(session)
{
  if (session.SharedMarch)
  {
    session.Rounds = std::make_unique<MarchRounds>(*session.SharedMarch);
  }
}

RenderSession::FrameRounds::~FrameRounds()
{
  if (this->Session.Rounds)
  {
    this->Session.Rounds->stop();
    this->Session.Rounds.reset();
  }
}

void RenderSession::shareMarch(std::optional<MarchShare> share)
{
  if (share && share->Shares > 1)
  {
    if (share->Share < 0 || share->Share >= share->Shares)
    {
      throw std::invalid_argument("shareMarch: Share " + std::to_string(share->Share) + " is not one of the " +
        std::to_string(share->Shares) + " shares.");
    }
    if (!share->Round)
    {
      throw std::invalid_argument("shareMarch: a march shared by processes needs a Round to exchange its rays through.");
    }
    if (this->MarchPieces > 1)
    {
      throw std::invalid_argument("shareMarch: a march shared by processes cannot also be forwarded through "
                                  "MarchPieces pieces in one process.");
    }
  }
  this->cancelFrame();
  this->SharedMarch = share && share->Shares > 1 ? share : std::nullopt;
}

// The pieces the march's rays are forwarded between: a shared march's
// shares, or MarchPieces in one process.
int RenderSession::marchPieces() const
{
  return this->SharedMarch ? this->SharedMarch->Shares : this->MarchPieces;
}

// marchRegion's march shared by processes (shareMarch): each band's centre
// rays, then with PixelSamples above 1 the edge pixels' (refineEdgesShared),
// in rounds between the shares, a round after each band carrying whether
// every share goes on; then the highlight, on each share alone (every share
// holds every pixel), and a last round saying whether all completed, so
// that nothing after it that one share does keeps another waiting. A
// failure within the rounds tells the others.
bool RenderSession::marchRegionShared(const FrameSetup& setup, const ComputePipeline& march, const MarchTarget& target,
  Progress& progress, double from, double to)
{
  const std::array<int, 4>& rect = target.Rect;
  MarchRounds& rounds = *this->Rounds;
  rounds.Words = rayStateWords(setup);
  const double refined = from + (to - from) * 0.9;
  try
  {
    for (int firstRow = 0; firstRow < rect[3];)
    {
      const int rows = this->marchBandRows(rect, firstRow, sharedBandPixels(rounds.Words), gpu::MarchGroupSide);
      bool goesOn = true;
      this->forMarchColumns(gpu::MarchPixels, rect[2], firstRow, rows,
        [&](const gpu::MarchWork& work, std::uint32_t groupsX, std::uint32_t groupsY) {
          goesOn = goesOn && this->marchShared(march, work, groupsX, groupsY, rounds);
        });
      firstRow += rows;
      if (!goesOn || !rounds.exchange({ progress.report(from + (to - from) * 0.8 * firstRow / rect[3]) ? 1u : 0u }))
      {
        return false;
      }
    }
    const bool refine = target.PixelSamples > 1;
    if (!this->selectShared(march, rect, refine, rounds) ||
      (refine && !this->refineEdgesShared(march, target.PixelSamples, rect, progress, refined, rounds)))
    {
      return false;
    }
    const bool completed = this->shadeHighlight(progress, refined) && progress.report(to);
    return rounds.exchange({ completed ? 1u : 0u });
  }
  catch (...)
  {
    rounds.stop();
    throw;
  }
}

// After a shared march's bands, as marchRegion's last band records them:
// with the edge pixels refined (`refine`) the ring's centre rays and the
// edge select; then the highlight's select (each share holds every pixel).
// False where a share stopped.
bool RenderSession::selectShared(
  const ComputePipeline& march, const std::array<int, 4>& rect, bool refine, MarchRounds& rounds)
{
  const int ring = MARCH_RING_PIXELS(rect[2], rect[3]);
  if (refine && !this->marchShared(march, ringWork(ring), queuedGroups(ring), 1, rounds))
  {
    return false;
  }
  this->Context->submitAndWait([&](VkCommandBuffer commands) {
    if (refine)
    {
      this->Buffers->EdgeQueue->recordClear(commands);
      this->recordMarchRows(commands, march, gpu::MarchSelectEdges, rect[2], 0, rect[3]);
    }
    this->recordHighlightSelect(commands, rect);
  });
  return true;
}

// refineEdges for a shared march: each stage's sub-rays, SharedRefinePixels
// queued pixels a dispatch, after share 0's queue went to every share (the
// select and the first stage queue pixels in each device's own order, and a
// ray's slot is its pixel's place in the queue); a round after each
// dispatch's pixels carries the progress (at `at`). False where a share stopped.
bool RenderSession::refineEdgesShared(const ComputePipeline& march, int pixelSamples, const std::array<int, 4>& rect,
  Progress& progress, double at, MarchRounds& rounds)
{
  const int n = pixelSamples;
  const auto stage = [&](int queue, int fromRay, int toRay) {
    if (!this->shareEdgeQueue(rounds, queue, static_cast<std::uint64_t>(rect[2]) * static_cast<std::uint64_t>(rect[3])))
    {
      return false;
    }
    const std::int64_t queued = queuedCount(*this->Buffers->EdgeQueue, queue);
    for (std::int64_t first = 0; first < queued; first += SharedRefinePixels)
    {
      const std::int64_t count = std::min(SharedRefinePixels, queued - first);
      for (int subRay = fromRay; subRay < toRay; ++subRay)
      {
        if (!this->marchShared(march, refineWork(first, count, subRay), queuedGroups(count), 1, rounds))
        {
          return false;
        }
      }
      if (!rounds.exchange({ progress.report(at) ? 1u : 0u }))
      {
        return false;
      }
    }
    return true;
  };
  return stage(0, 0, n) && stage(1, n, n * n);
}

// Share 0's edge queue `queue` written over every other share's, in a
// round: the queues' counts and the queue's pixels (the first stage's from
// the first entry, the second's from `rectPixels`), those it holds alone
// (the buffers' sizes follow each share's frames). False where a share stopped.
bool RenderSession::shareEdgeQueue(MarchRounds& rounds, int queue, std::uint64_t rectPixels)
{
  VulkanBuffer& counts = *this->Buffers->EdgeQueue;
  VulkanBuffer& pixels = *this->Buffers->EdgePixels;
  const std::uint64_t countWords = counts.size() / sizeof(std::uint32_t);
  const std::uint64_t offset = (queue == 0 ? 0 : rectPixels) * sizeof(std::uint32_t);
  const auto into = [](std::uint32_t* words) {
    return [words](std::uint64_t first, std::uint64_t count, const void* from) {
      std::memcpy(reinterpret_cast<char*>(words) + first, from, count);
    };
  };
  std::vector<std::uint32_t> post{ 1 };
  if (this->SharedMarch->Share == 0)
  {
    post.resize(1 + countWords + static_cast<std::uint64_t>(queuedCount(counts, queue)));
    counts.read(counts.size(), into(post.data() + 1));
    pixels.readRange(offset, (post.size() - 1 - countWords) * sizeof(std::uint32_t), into(post.data() + 1 + countWords));
  }
  std::vector<std::uint32_t> first;
  const bool goesOn = rounds.exchange(post, [&](int share, const std::uint32_t* words, std::uint64_t count) {
    if (share == 0)
    {
      first.assign(words, words + count);
    }
    return share != 0 || (count >= countWords && offset + (count - countWords) * sizeof(std::uint32_t) <= pixels.size());
  });
  if (goesOn && this->SharedMarch->Share != 0)
  {
    counts.write(0, counts.size(), first.data());
    if (first.size() > countWords)
    {
      pixels.write(offset, (first.size() - countWords) * sizeof(std::uint32_t), first.data() + countWords);
    }
  }
  return goesOn;
}

namespace
{
// A post of `words` words, its first (whether the share goes on) `goesOn`.
std::vector<char> postOf(std::uint64_t words, std::uint32_t goesOn)
{
  std::vector<char> post(words * sizeof(std::uint32_t));
  std::memcpy(post.data(), &goesOn, sizeof(goesOn));
  return post;
}

// The post of the rays a share took up in a round, each its slot and state,
// written into `held`: `after` holds the states of `slots` read back, in
// their order. In the first round (`started`) it is `held` itself, read
// straight into (every slot), and a slot no ray has (it keeps KeptDone) is
// not posted. Sized before it is filled: a band's states are not copied again.
std::vector<char> takenUp(std::vector<std::uint32_t>& held, const std::vector<std::uint32_t>& slots,
  const std::uint32_t* after, std::uint64_t words, bool started)
{
  const auto posted = [&](std::size_t i) { return !started || after[i * words] != gpu::KeptDone; };
  std::uint64_t rays = 0;
  for (std::size_t i = 0; i < slots.size(); ++i)
  {
    rays += posted(i) ? 1 : 0;
  }
  std::vector<char> post = postOf(1 + rays * (1 + words), 1);
  char* at = post.data() + sizeof(std::uint32_t);
  for (std::size_t i = 0; i < slots.size(); ++i)
  {
    const std::uint32_t* state = after + i * words;
    if (!posted(i))
    {
      continue;
    }
    std::memcpy(at, &slots[i], sizeof(std::uint32_t));
    std::memcpy(at + sizeof(std::uint32_t), state, words * sizeof(std::uint32_t));
    at += (1 + words) * sizeof(std::uint32_t);
    if (!started)
    {
      std::copy_n(state, words, held.begin() + static_cast<std::ptrdiff_t>(slots[i] * words));
    }
  }
  return post;
}

// A run of consecutive slots: its first index in the slots, its first slot, its length.
struct SlotRun
{
  std::size_t Index;
  std::uint64_t Slot, Count;
};

// `slots` (sorted) as runs of consecutive slots (readRuns and writeRuns
// stage them in batches, as fill does its rounds).
std::vector<SlotRun> slotRuns(const std::vector<std::uint32_t>& slots)
{
  std::vector<SlotRun> runs;
  for (std::size_t first = 0, end = 0; first < slots.size(); first = end)
  {
    for (end = first + 1; end < slots.size() && slots[end] == slots[end - 1] + 1; ++end)
    {
    }
    runs.push_back({ first, slots[first], end - first });
  }
  return runs;
}
} // namespace

// One dispatch's work of a shared march: share 0 starts every ray in the
// first round; in each round after, every share takes up the rays held in
// its layers (forwardShared); then every share writes every finished ray's
// pixel. False where a share stopped.
bool RenderSession::marchShared(const ComputePipeline& march, gpu::MarchWork work, std::uint32_t groupsX,
  std::uint32_t groupsY, MarchRounds& rounds)
{
  const MarchShare& share = *this->SharedMarch;
  const std::pair<int, int> layers = evenShare(this->Volume->Shape.Dimensions[2], share.Share, share.Shares);
  work.piece = gpu::ivec2(layers.first, layers.second);
  work.sharesRays = 1;
  const std::uint64_t slots = std::uint64_t(groupsX) * groupsY * gpu::MarchGroupSide * gpu::MarchGroupSide;
  rounds.begin(slots);
  const SharedForwarding pass{ layers, { 0, share.Share == 0 ? slots : 0 }, MarchSweeps * (share.Shares - 1) + 2,
    "view march", "rays", true, [&](bool started, const std::vector<std::uint32_t>&) {
      work.resumed = started ? gpu::MarchStartsRays : gpu::MarchResumesRays;
      this->dispatchShared(march, work, groupsX, groupsY, rounds);
    } };
  if (!this->forwardShared(pass, rounds))
  {
    return false;
  }
  work.resumed = gpu::MarchWritesFinished;
  this->dispatchShared(march, work, groupsX, groupsY, rounds);
  return true;
}

// The rounds of a forwarded pass's work shared by processes: in the first,
// each share starts the states of its `Started` slots; in each round after,
// every share takes up the states held in its layers; each round's states go
// to every share (MarchRounds) until none goes on, within MostRounds (a
// longer path is refused alike by every share: no partial result). A
// failure in a round posts that this share stops where the pass
// `StopsInRound` (the march); otherwise it leaves the rounds to its step's
// last exchange. False where a share stopped.
bool RenderSession::forwardShared(const SharedForwarding& pass, MarchRounds& rounds)
{
  const int shares = rounds.shares();
  for (int round = 0; round == 0 || !rounds.Live.empty(); ++round)
  {
    if (round == pass.MostRounds)
    {
      throw std::runtime_error("The " + pass.Pass + " shared by " + std::to_string(shares) + " processes left " +
        pass.States + " unfinished after " + std::to_string(pass.MostRounds) + " rounds; no image is given.");
    }
    std::vector<char> post = postOf(1, 1);
    std::vector<std::uint32_t> slots; // the round's on this share
    std::exception_ptr failure;
    try
    {
      post = this->forwardedRound(pass, rounds, round == 0, slots);
    }
    catch (...)
    {
      if (!pass.StopsInRound)
      {
        throw;
      }
      failure = std::current_exception();
      post = postOf(1, 0);
    }
    const bool goesOn = rounds.exchangeRays(post);
    if (failure)
    {
      std::rethrow_exception(failure);
    }
    if (!goesOn && !pass.StopsInRound && !rounds.exchangeEnded())
    {
      // Not this pass's way to stop: end the rounds by the step's last exchange.
      throw std::runtime_error("A share posted to the " + pass.Pass + "'s round that it stops; no image is given.");
    }
    if (!goesOn)
    {
      return false;
    }
    rounds.live(slots);
  }
  return true;
}

// A round of forwardShared on this share: its `slots` (the first round's
// started, then the live ones held in its layers) dispatched, their states
// read back (the first round's straight into Held) and posted. A share
// starting none in the first round dispatches nothing there.
std::vector<char> RenderSession::forwardedRound(
  const SharedForwarding& pass, MarchRounds& rounds, bool started, std::vector<std::uint32_t>& slots)
{
  const auto [first, end] = pass.Started;
  if (started && first == end)
  {
    return postOf(1, 1);
  }
  if (started)
  {
    for (std::uint64_t slot = first; slot < end; ++slot)
    {
      slots.push_back(static_cast<std::uint32_t>(slot));
    }
  }
  else
  {
    slots = rounds.liveIn(pass.Layers);
  }
  pass.Dispatch(started, slots);
  std::vector<std::uint32_t> after(started ? 0 : slots.size() * rounds.Words);
  std::uint32_t* states = started ? rounds.Held.data() + first * rounds.Words : after.data();
  this->readRayStates(slots, rounds, states);
  return takenUp(rounds.Held, slots, states, rounds.Words, started);
}

// A dispatch of `work` in a shared march on this share, after the states the
// device lacks are written (writeFreshStates), reading its piece's fields
// alone with VulkanOptions::MarchPieceFieldsOnly (recordPieceFields).
void RenderSession::dispatchShared(const ComputePipeline& march, const gpu::MarchWork& work, std::uint32_t groupsX,
  std::uint32_t groupsY, MarchRounds& rounds)
{
  this->writeFreshStates(rounds);
  const std::vector<PieceField> fields = this->pieceFields();
  this->Context->submitAndWait([&](VkCommandBuffer commands) {
    this->recordPieceFields(commands, fields, { work.piece.x, work.piece.y });
    march.dispatch(commands, work, groupsX, groupsY);
    this->recordWholeFields(commands, fields);
  });
}

// The states the device's buffer lacks written from Held: all of them the
// first time, then the slots other shares posted since (Fresh), as runs.
void RenderSession::writeFreshStates(MarchRounds& rounds)
{
  const auto start = Clock::now();
  VulkanBuffer& states = *this->Buffers->RayStates;
  const std::uint64_t bytes = rounds.Words * sizeof(std::uint32_t);
  if (!rounds.DeviceHolds)
  {
    states.write(0, rounds.Held.size() * sizeof(std::uint32_t), rounds.Held.data());
  }
  else
  {
    std::sort(rounds.Fresh.begin(), rounds.Fresh.end());
    rounds.Fresh.erase(std::unique(rounds.Fresh.begin(), rounds.Fresh.end()), rounds.Fresh.end());
    std::vector<WrittenRun> runs;
    std::vector<const char*> from;
    for (const SlotRun& run : slotRuns(rounds.Fresh))
    {
      runs.push_back({ &states, run.Slot * bytes, run.Count * bytes });
      from.push_back(reinterpret_cast<const char*>(rounds.Held.data() + run.Slot * rounds.Words));
    }
    writeRuns(runs, from);
  }
  rounds.Fresh.clear();
  rounds.DeviceHolds = true;
  rounds.Seconds += secondsSince(start);
}

// The states of `slots` (sorted) after a shared march's dispatch, into
// `after` in their order.
void RenderSession::readRayStates(const std::vector<std::uint32_t>& slots, MarchRounds& rounds, std::uint32_t* after) const
{
  const auto start = Clock::now();
  const std::uint64_t bytes = rounds.Words * sizeof(std::uint32_t);
  std::vector<ReadRun> runs;
  std::vector<char*> into;
  for (const SlotRun& run : slotRuns(slots))
  {
    runs.push_back({ this->Buffers->RayStates.get(), run.Slot * bytes, run.Count * bytes });
    into.push_back(reinterpret_cast<char*>(after + run.Index * rounds.Words));
  }
  readRuns(runs, into);
  rounds.Seconds += secondsSince(start);
}

} // namespace opal
