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
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

// The rounds of a shared march (shareMarch): each round every share's post
// goes to every share: whether it goes on, then each ray it took up, its
// slot and its state's words. Held, the rays of the dispatch being marched,
// is alike on every share after each round. Once a share stopped, or the
// exchange ended, there is no round more.
class RenderSession::MarchRounds
{
public:
  MarchRounds(const MarchShare& share, std::uint64_t words)
    : Share(share)
    , Words(words)
  {
  }

  std::vector<std::uint32_t> Held; // RAY_STATE_WORDS per slot; KeptDone where no ray is

  std::uint64_t words() const { return this->Words; }

  // Sends `post`; each other share's rays written into Held. Whether every share goes on.
  bool exchange(const std::vector<std::uint32_t>& post)
  {
    std::vector<char> bytes(post.size() * sizeof(std::uint32_t));
    std::memcpy(bytes.data(), post.data(), bytes.size());
    std::vector<std::vector<char>> received(static_cast<std::size_t>(this->Share.Shares));
    const auto sink = [&](int share, std::uint64_t first, std::uint64_t count, const char* from) {
      if (share >= 0 && share < this->Share.Shares)
      {
        std::vector<char>& into = received[static_cast<std::size_t>(share)];
        into.resize(std::max<std::size_t>(into.size(), first + count));
        std::memcpy(into.data() + first, from, count);
      }
    };
    this->Ended = true; // a throw ends it too
    bool goesOn = this->Share.Round(bytes, sink) && post.at(0) != 0;
    for (int share = 0; share < this->Share.Shares; ++share)
    {
      goesOn = (share == this->Share.Share || this->take(received[static_cast<std::size_t>(share)])) && goesOn;
    }
    this->Ended = !goesOn;
    return goesOn;
  }

  // A round saying this share stops, unless the rounds are over.
  void stop()
  {
    if (!this->Ended)
    {
      try
      {
        this->exchange({ 0 });
      }
      catch (...)
      {
        // The failure being rethrown is the one to report.
      }
    }
  }

private:
  // Another share's post written into Held: false where it stopped (or
  // sent what no share posts).
  bool take(const std::vector<char>& bytes)
  {
    const std::uint64_t record = (1 + this->Words) * sizeof(std::uint32_t);
    if (bytes.size() < sizeof(std::uint32_t) || (bytes.size() - sizeof(std::uint32_t)) % record != 0 || bytes[0] == 0)
    {
      return false;
    }
    const std::uint64_t slots = this->Held.size() / this->Words;
    for (std::uint64_t at = sizeof(std::uint32_t); at < bytes.size(); at += record)
    {
      std::uint32_t slot = 0;
      std::memcpy(&slot, bytes.data() + at, sizeof(slot));
      if (slot >= slots)
      {
        return false;
      }
      std::memcpy(this->Held.data() + slot * this->Words, bytes.data() + at + sizeof(slot), record - sizeof(slot));
    }
    return true;
  }

  const MarchShare& Share;
  std::uint64_t Words;
  bool Ended = false;
};

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
// rays in rounds between the shares, then a round carrying whether every
// share goes on; then the highlight, on each share alone (every share holds
// every pixel). A failure before the rounds are over tells the others.
bool RenderSession::marchRegionShared(const FrameSetup& setup, const ComputePipeline& march, const MarchTarget& target,
  Progress& progress, double from, double to)
{
  if (target.PixelSamples > 1)
  {
    throw std::invalid_argument("PixelSamples " + std::to_string(target.PixelSamples) +
      ": the edge pixels' sub-rays are not yet marched by processes sharing the volume; render with PixelSamples 1.");
  }
  const std::array<int, 4>& rect = target.Rect;
  MarchRounds rounds(*this->SharedMarch, rayStateWords(setup));
  try
  {
    for (int firstRow = 0; firstRow < rect[3];)
    {
      const int rows = this->marchBandRows(rect, firstRow);
      const auto start = Clock::now();
      bool goesOn = true;
      this->forMarchColumns(gpu::MarchPixels, rect[2], firstRow, rows,
        [&](const gpu::MarchWork& work, std::uint32_t groupsX, std::uint32_t groupsY) {
          goesOn = goesOn && this->marchShared(march, work, groupsX, groupsY, rounds);
        });
      if (!goesOn)
      {
        return false;
      }
      this->MarchPacer.measured(static_cast<std::int64_t>(rows) * marchGroups(rect[2]) * gpu::MarchGroupSide, secondsSince(start));
      firstRow += rows;
      const bool going = progress.report(from + (to - from) * 0.8 * firstRow / rect[3]);
      if (!rounds.exchange({ going ? 1u : 0u }))
      {
        return false;
      }
    }
  }
  catch (...)
  {
    rounds.stop();
    throw;
  }
  this->Context->submitAndWait([&](VkCommandBuffer commands) { this->recordHighlightSelect(commands, rect); });
  return this->shadeHighlight(progress, from + (to - from) * 0.9) && progress.report(to);
}

namespace
{
// Whether a ray of `held` (`words` per slot) goes on in a piece.
bool raysGoOn(const std::vector<std::uint32_t>& held, std::uint64_t words)
{
  for (std::uint64_t at = 0; at < held.size(); at += words)
  {
    if (held[at] < gpu::KeptUnwritten)
    {
      return true;
    }
  }
  return false;
}

// The post of the rays a share took up in a round, `after` its states read
// back: in the first (`started`) every ray it started (a slot no ray has
// keeps KeptDone), later those held in `layers` before; those written into `held`.
std::vector<std::uint32_t> takenUp(
  std::vector<std::uint32_t>& held, const std::vector<std::uint32_t>& after, std::uint64_t words, bool started,
  std::pair<int, int> layers)
{
  std::vector<std::uint32_t> post{ 1 };
  for (std::uint64_t at = 0; at < held.size(); at += words)
  {
    const std::uint32_t before = held[at];
    const bool took = started ? after[at] != gpu::KeptDone
                              : before < gpu::KeptUnwritten && static_cast<int>(before) >= layers.first &&
        static_cast<int>(before) < layers.second;
    if (took)
    {
      post.push_back(static_cast<std::uint32_t>(at / words));
      post.insert(post.end(), after.begin() + static_cast<std::ptrdiff_t>(at),
        after.begin() + static_cast<std::ptrdiff_t>(at + words));
      std::copy_n(after.begin() + static_cast<std::ptrdiff_t>(at), words, held.begin() + static_cast<std::ptrdiff_t>(at));
    }
  }
  return post;
}
} // namespace

// One dispatch's work of a shared march: share 0 starts every ray in the
// first round; in each round after, every share takes up the rays held in
// its layers; each round's rays go to every share (MarchRounds) until none
// goes on, within MarchSweeps sweeps' worth of rounds (a longer path is
// refused alike by every share: no partial image); then every share writes
// every finished ray's pixel. False where a share stopped.
bool RenderSession::marchShared(const ComputePipeline& march, gpu::MarchWork work, std::uint32_t groupsX,
  std::uint32_t groupsY, MarchRounds& rounds)
{
  const MarchShare& share = *this->SharedMarch;
  const std::pair<int, int> layers = evenShare(this->Volume->Shape.Dimensions[2], share.Share, share.Shares);
  work.piece = gpu::ivec2(layers.first, layers.second);
  work.sharesRays = 1;
  const std::uint64_t words = rounds.words();
  const std::uint64_t slots = std::uint64_t(groupsX) * groupsY * gpu::MarchGroupSide * gpu::MarchGroupSide;
  const std::uint64_t bytes = slots * words * sizeof(std::uint32_t);
  rounds.Held.assign(slots * words, gpu::KeptDone);
  const int mostRounds = MarchSweeps * share.Shares + 1;
  for (int round = 0; round == 0 || raysGoOn(rounds.Held, words); ++round)
  {
    if (round > mostRounds)
    {
      throw std::runtime_error("The view march shared by " + std::to_string(share.Shares) +
        " processes left rays unfinished after " + std::to_string(mostRounds) + " rounds; no image is given.");
    }
    const bool started = round == 0;
    std::vector<std::uint32_t> post{ 0 };
    std::exception_ptr failure;
    try
    {
      this->Buffers->RayStates->write(0, bytes, rounds.Held.data());
      work.resumed = started ? gpu::MarchStartsRays : gpu::MarchResumesRays;
      post = { 1 };
      if (!started || share.Share == 0)
      {
        this->submitSharedDispatch(march, work, groupsX, groupsY);
        std::vector<std::uint32_t> after(slots * words);
        this->Buffers->RayStates->read(bytes, [&](std::uint64_t first, std::uint64_t count, const void* from) {
          std::memcpy(reinterpret_cast<char*>(after.data()) + first, from, count);
        });
        post = takenUp(rounds.Held, after, words, started, layers);
      }
    }
    catch (...)
    {
      failure = std::current_exception();
      post = { 0 };
    }
    const bool goesOn = rounds.exchange(post);
    if (failure)
    {
      std::rethrow_exception(failure);
    }
    if (!goesOn)
    {
      return false;
    }
  }
  this->Buffers->RayStates->write(0, bytes, rounds.Held.data());
  work.resumed = gpu::MarchWritesFinished;
  this->submitSharedDispatch(march, work, groupsX, groupsY);
  return true;
}

// A shared march's dispatch of `work`, in one submit, reading its piece's
// fields alone with VulkanOptions::MarchPieceFieldsOnly (recordPieceFields).
void RenderSession::submitSharedDispatch(
  const ComputePipeline& march, const gpu::MarchWork& work, std::uint32_t groupsX, std::uint32_t groupsY)
{
  const std::vector<PieceField> fields = this->pieceFields();
  this->Context->submitAndWait([&](VkCommandBuffer commands) {
    this->recordPieceFields(commands, fields, { work.piece.x, work.piece.y });
    march.dispatch(commands, work, groupsX, groupsY);
    this->recordWholeFields(commands, fields);
  });
}

} // namespace opal
