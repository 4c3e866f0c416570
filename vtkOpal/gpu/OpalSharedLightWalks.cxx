// The walks to the light of a light pass shared by processes whose sessions
// hold their pieces (RenderSession::holdPiece, docs/design.md §8.1),
// forwarded between the pieces as one process's are between MarchPieces
// (OpalForwardedMarch.cxx), in the shared march's rounds (forwardShared):
// each share starts the walks of its own voxels, a walk needing another
// share's layers goes on there, and its light is stored back in its own
// voxel's share, so that a share reads its piece's medium and halo alone.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"
#include "OpalShareSlabs.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

// A shared light pass's forwarded walks: the rounds (over the pass's
// `round`s), the fields a share reads by piece (MarchPieceFieldsOnly), and
// the slots of each share's walks in a work (share s's from s * PerShare).
struct RenderSession::SharedWalks
{
  SharedWalks(const MarchShare& share, std::uint64_t perShare)
    : Share(share)
    , Rounds(this->Share)
    , PerShare(perShare)
  {
  }

  MarchShare Share;
  MarchRounds Rounds;
  std::vector<PieceField> Fields;
  std::uint64_t PerShare;
};

// The forwarded walks of this session's piece (HeldPiece) through `round`,
// PerShare walks of each share a work: their states' buffer, the piece
// fields (a test's option) and the rounds made ready.
std::unique_ptr<RenderSession::SharedWalks> RenderSession::beginSharedWalks(const LayerExchange& round, std::uint64_t perShare)
{
  const auto [share, shares] = this->HeldPiece;
  auto walks = std::make_unique<SharedWalks>(MarchShare{ share, shares, round }, perShare);
  const std::uint64_t slots = static_cast<std::uint64_t>(shares) * perShare;
  this->prepareRayStates(slots * gpu::LightStateWords * sizeof(std::uint32_t));
  this->preparePieceFields(shares);
  walks->Fields = this->lightPieceFields(shares);
  walks->Rounds.Words = gpu::LightStateWords;
  walks->Rounds.begin(slots);
  return walks;
}

// One work of the shared walks: this share starts `started` walks, and each
// round's dispatch takes up, of each share s whose walks it holds, the first
// `reach` of its slots, `workOf(s, resumed, reach)` saying which voxels
// (first, count, layer) of `pass`. False where a share stopped; a failure
// throws, leaving the rounds to the step's last exchange.
bool RenderSession::walkShared(SharedWalks& walks, const ComputePipeline& pass, std::uint64_t started, const WalkWork& workOf)
{
  const auto [share, shares] = this->HeldPiece;
  const std::pair<int, int> layers = evenShare(this->Volume->Shape.Dimensions[2], share, shares);
  const std::uint64_t perShare = walks.PerShare;
  const std::uint64_t own = static_cast<std::uint64_t>(share) * perShare;
  if (started > perShare)
  {
    throw std::logic_error("walkShared: a share's walks beyond its slots.");
  }
  const SharedForwarding work{ layers, { own, own + started }, LightWalkSweeps * (shares - 1) + 2, "light pass",
    "walks to the light", false, [&](bool first, const std::vector<std::uint32_t>& slots) {
      if (slots.empty())
      {
        return; // none held here: the fresh states wait for the next dispatch
      }
      this->writeFreshStates(walks.Rounds);
      std::vector<std::uint64_t> reach(static_cast<std::size_t>(shares), 0);
      for (const std::uint32_t slot : slots)
      {
        std::uint64_t& r = reach[slot / perShare];
        r = std::max<std::uint64_t>(r, slot % perShare + 1);
      }
      this->Context->submitAndWait([&](VkCommandBuffer commands) {
        this->recordPieceFields(commands, walks.Fields, layers);
        for (int s = 0; s < shares; ++s)
        {
          const std::uint64_t taken = reach[static_cast<std::size_t>(s)];
          if (taken == 0)
          {
            continue;
          }
          gpu::LightPassWork dispatched = workOf(s, !first, taken);
          dispatched.resumed = first ? 0 : 1;
          dispatched.piece = gpu::ivec2(layers.first, layers.second);
          dispatched.slotFirst = static_cast<std::int32_t>(static_cast<std::uint64_t>(s) * perShare);
          pass.dispatch(commands, dispatched,
            static_cast<std::uint32_t>((taken + gpu::LightPassGroupSize - 1) / gpu::LightPassGroupSize));
        }
        this->recordWrittenBack(commands, walks.Fields, layers);
        this->recordWholeFields(commands, walks.Fields);
      });
    } };
  return this->forwardShared(work, walks.Rounds);
}

// The walks from every voxel (the light low or to the side): in each work
// every share starts those of its next SharedLightWalks voxels of its rows.
// False where a share stopped (`exchanging` false: a round ended the
// exchange) or the progress aborts.
bool RenderSession::marchLightShared(bool braggShadow, Progress& progress, const LayerExchange& round, bool& exchanging)
{
  const auto shares = this->HeldPiece.second;
  const std::array<int, 3> dims = this->Volume->Shape.Dimensions;
  const auto walks = static_cast<std::size_t>(SharedLightWalks);
  // Work k's voxels of share s: the kth run of its slab (none past its end).
  const auto workOf = [&](int s, std::size_t k) { return slabChunk(shareSlab(dims, s, shares), walks, k); };
  const std::size_t works = slabChunks(dims, shares, walks); // alike on every share
  const ComputePipeline& pass = this->lightPass(gpu::LightPassMarchTowardsLight, braggShadow, true);
  const std::unique_ptr<SharedWalks> shared = this->beginSharedWalks(round, walks);
  for (std::size_t k = 0; k < works; ++k)
  {
    const auto [first, end] = workOf(this->HeldPiece.first, k);
    exchanging = this->walkShared(*shared, pass, end - first, [&](int s, bool, std::uint64_t) {
      const auto [from, to] = workOf(s, k);
      return gpu::LightPassWork{ static_cast<std::uint32_t>(from), static_cast<std::int32_t>(to - from), 0, 0,
        gpu::ivec2(0, 0), 0, 0 };
    }); // a throw leaves it as it was: the step's last exchange ends it
    if (!exchanging || !progress.stageDone(static_cast<double>(k + 1) / static_cast<double>(works)))
    {
      return false;
    }
  }
  return true;
}

// The shared walks of the sweep from above: the walks to the light of
// layer y = `layer`'s queue (its skin voxels of this share's rows, which the
// layer's sweep queued), each share's queue holding at most the voxels of
// the most rows a share has.
bool RenderSession::walkQueueShared(SharedWalks& walks, const ComputePipeline& enter, int layer)
{
  const std::int64_t queued = this->queuedCount(*this->Volume->EntryQueues, layer);
  return this->walkShared(walks, enter, static_cast<std::uint64_t>(queued), [layer](int, bool resumed, std::uint64_t taken) {
    // The share's own queue as the sweep left it (count 0), or in a later
    // round `taken` walks of a share's queue (this share's too), each walk's
    // voxel kept with it: this device's queue may be another share's.
    return gpu::LightPassWork{ 0, resumed ? static_cast<std::int32_t>(taken) : 0, layer, 0, gpu::ivec2(0, 0), 0, 0 };
  });
}

// The sweep from above of a light pass shared by processes whose sessions
// hold their pieces: each layer's sweep of this share's `rows`, then the
// layer's queued walks shared (walkQueueShared), then `afterLayer` (the
// rows the shares beside read). False as marchLightShared.
bool RenderSession::sweepLightShared(bool braggShadow, Progress& progress, std::pair<int, int> rows,
  const std::function<bool(int layer)>& afterLayer, const LayerExchange& round, bool& exchanging)
{
  const std::unique_ptr<SharedWalks> shared = this->beginSharedWalks(round, this->queuedWalksPerShare());
  const ComputePipeline& enter = this->lightPass(gpu::LightPassMarchQueued, braggShadow, true);
  return this->sweepLightLayers(braggShadow, progress, rows, afterLayer, [&](int layer) {
    exchanging = this->walkQueueShared(*shared, enter, layer); // a throw leaves it as it was
    return exchanging;
  });
}

// The slots of each share's queued walks of a layer (walkQueueShared): the
// voxels of a layer in the most rows z a share holds.
std::uint64_t RenderSession::queuedWalksPerShare() const
{
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  return static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(std::max(mostInShare(dims[2], this->HeldPiece.second), 1));
}

} // namespace opal
