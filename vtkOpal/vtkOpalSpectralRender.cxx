#include "vtkOpalSpectralRender.h"

#include "OpalRenderCamera.h"
#include "OpalRenderParameters.h"
#include "OpalRenderSession.h"
#include "OpalVulkanError.h"
#include "vtkOpalRenderInput.h"
#include "vtkOpalRankAgreement.h"
#include "vtkOpalRankWait.h"
#include "vtkOpalSharedLightField.h"
#include "vtkOpalSharedMarch.h"
#include "vtkOpalSharedScatteredLight.h"
#include "vtkOpalRenderOutput.h"
#include "vtkOpalVolumePieces.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpalArrayCopy.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

vtkStandardNewMacro(vtkOpalSpectralRender);

namespace
{
// A sentence to continue after a semicolon.
std::string withoutFullStop(std::string sentence)
{
  if (!sentence.empty() && sentence.back() == '.')
  {
    sentence.pop_back();
  }
  return sentence;
}
} // namespace

vtkOpalSpectralRender::vtkOpalSpectralRender()
{
  // The table's defaults; 0 where a row takes the volume's value.
  opal::RenderParameters defaults;
  for (const auto& row : opal::renderParameterRows())
  {
    if (row.FromVolume)
    {
      row.Set(defaults, std::vector<double>(row.Components, 0.0));
    }
  }
  this->SetRenderParameters(defaults);
  this->DeviceIndex = -1;
  this->DeviceMemoryLimit = 0;
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkOpalSpectralRender::~vtkOpalSpectralRender()
{
  this->EndSession();
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkOpalSpectralRender, Controller, vtkMultiProcessController);

opal::RenderParameters vtkOpalSpectralRender::GetRenderParameters() const
{
  opal::RenderParameters p;
  OPAL_RENDER_PARAMETERS(OPAL_VTK_TO_STRUCT)
  return p;
}

void vtkOpalSpectralRender::SetRenderParameters(const opal::RenderParameters& p)
{
  OPAL_RENDER_PARAMETERS(OPAL_VTK_FROM_STRUCT)
  this->Modified();
}

int vtkOpalSpectralRender::GetNumberOfValidationMessages() const
{
  return this->ValidationMessages;
}

opal::ResolvedFrame vtkOpalSpectralRender::GetResolvedFrame(vtkInformation* inputInformation, vtkImageData* input) const
{
  return this->Resolve(this->GetRenderParameters(), inputInformation, input);
}

opal::ResolvedFrame vtkOpalSpectralRender::Resolve(
  const opal::RenderParameters& parameters, vtkInformation* inputInformation, vtkImageData* input) const
{
  // The image a preview renders is the smaller one: extent and data agree.
  return opal::resolveFrame(
    parameters, vtkOpalRenderInput::ReadSettings(inputInformation, input), this->PresetPlacement);
}

int vtkOpalSpectralRender::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkOpalSpectralRender::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const opal::ResolvedFrame resolved = this->GetResolvedFrame(inputVector[0]->GetInformationObject(0));
  const opal::RenderParameters& p = resolved.Parameters;
  const std::string& error = resolved.Error;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!error.empty())
  {
    if (error != this->ReportedError || this->GetMTime() != this->ReportedErrorTime)
    {
      vtkErrorMacro(<< error);
      this->ReportedError = error;
      this->ReportedErrorTime = this->GetMTime();
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->AnnouncedExtent, 6);
    return 0;
  }
  this->ReportedError.clear();
  // VTK image rows run bottom to top; ImageRegion counts from the top.
  opal::RenderImage frame;
  frame.ImageSize = p.ImageSize;
  frame.Region = opal::renderedRegion(p);
  vtkOpalRenderOutput::ExtentOf(frame, this->AnnouncedExtent);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->AnnouncedExtent, 6);
  const double spacing[3] = { 1, 1, 1 };
  const double origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

int vtkOpalSpectralRender::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A request left over from an earlier image size (after a failed update)
  // is clipped to the image; one outside it asks for the whole image.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6], requested[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), requested);
  bool overlaps = true;
  for (int a = 0; a < 3; ++a)
  {
    requested[2 * a] = std::max(requested[2 * a], whole[2 * a]);
    requested[2 * a + 1] = std::min(requested[2 * a + 1], whole[2 * a + 1]);
    overlaps = overlaps && requested[2 * a] <= requested[2 * a + 1];
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), overlaps ? requested : whole, 6);

  // Every pixel may look through the whole volume: one process asks for all
  // of it; under MPI each rank asks for its piece and the ranks gather the
  // arrays the render reads (GatherVolume), whichever piece of the image
  // this rank renders.
  vtkOpalVolumePieces::AskForPiece(this->Controller, inputVector[0]->GetInformationObject(0));
  return 1;
}

opal::RenderSession& vtkOpalSpectralRender::Session()
{
  if (!this->HasSessionOfSettings())
  {
    if (this->DeviceMemoryLimit < 0)
    {
      throw std::invalid_argument(
        "DeviceMemoryLimit must be 0 (no limit) or a number of MB, got " + std::to_string(this->DeviceMemoryLimit));
    }
    this->EndSession();
    opal::VulkanOptions options;
    options.DeviceIndex = this->DeviceIndex; // below -1 the context refuses it
    options.MemoryLimitBytes = static_cast<std::uint64_t>(this->DeviceMemoryLimit) << 20;
    this->RenderSession = std::make_unique<opal::RenderSession>(options); // ended at exit by OpalGpu
    this->SessionDeviceIndex = this->DeviceIndex;
    this->SessionMemoryLimit = this->DeviceMemoryLimit;
  }
  return *this->RenderSession;
}

bool vtkOpalSpectralRender::HasSessionOfSettings() const
{
  return this->RenderSession && this->SessionDeviceIndex == this->DeviceIndex &&
    this->SessionMemoryLimit == this->DeviceMemoryLimit;
}

bool vtkOpalSpectralRender::HoldsUploadedVolume(vtkImageData* volume) const
{
  return volume && this->HasSessionOfSettings() && this->UploadedVolume == volume &&
    this->UploadedVolumeTime == volume->GetMTime() && this->RenderSession->holdsVolume();
}

// Whether the session's volume serves a frame of this rank, marched shared
// by the ranks or not: its medium held whole, or for its piece (a volume
// uploaded for another piece is uploaded again, its arrays gathered again).
bool vtkOpalSpectralRender::MediumServes(bool marchShared) const
{
  const auto [share, shares] = this->PieceHeld(marchShared);
  return this->RenderSession->mediumServes(share, shares);
}

// The piece of the volume's layers a rank's session holds: its own where the
// ranks march shared, else the whole (one share).
std::pair<int, int> vtkOpalSpectralRender::PieceHeld(bool marchShared) const
{
  return marchShared ? std::make_pair(vtkOpalRankAgreement::Rank(this->Controller), vtkOpalRankAgreement::Ranks(this->Controller))
                     : std::make_pair(0, 1);
}

bool vtkOpalSpectralRender::UploadVolume(vtkImageData* input, bool marchShared)
{
  opal::RenderSession& session = this->Session(); // a new session holds no volume
  const auto [share, shares] = this->PieceHeld(marchShared);
  const bool arraysHeld = this->Gathered.Serves({ share, shares });
  if (!session.mediumServes(share, shares) && !arraysHeld)
  {
    // Kept as it is: only the render's update gathers the arrays again.
    this->SayError("The render's device holds only this rank's piece of the medium (ShareMarch), and under MPI only "
                   "the render's update gathers the volume's arrays again: a frame of the whole volume (a background "
                   "frame) needs the render updated with ShareMarch off.");
    return false;
  }
  // A march shared by the ranks reads the light fields and the medium only
  // in the rank's piece: they hold it alone (docs/design.md §8.1), set before
  // the upload makes them; any other frame (a background frame too) reads
  // them whole, and drops a medium held by piece.
  session.holdPiece(share, shares);
  if (this->HoldsUploadedVolume(input))
  {
    return true;
  }
  if (!arraysHeld)
  {
    this->SayError("The render's device no longer holds the volume, whose arrays under MPI only the render's "
                   "update gathers again: update the render.");
    return false;
  }
  opal::RenderVolume volume;
  vtkOpalRenderInput::Storage storage;
  const std::string error = vtkOpalRenderInput::Read(input, volume, storage, this->Gathered.Medium());
  if (!error.empty())
  {
    this->SayError(error);
    return false;
  }
  this->UploadedVolume = nullptr; // until the upload succeeds
  session.setVolume(volume);
  this->Gathered.ReleaseArrays(); // under MPI 12 to 20 bytes per voxel: the device holds them now
  this->UploadedVolume = input;
  this->UploadedVolumeTime = input->GetMTime();
  return true;
}

int vtkOpalSpectralRender::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The session is this thread's again: a background frame (of other settings) stops.
  this->CancelBackgroundFrame();
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  FailedRequest request{ input, input ? input->GetMTime() : 0, this->GetMTime(), {} };
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), request.Extent.data());
  this->NoteMediumLayers(nullptr); // none until this request renders
  // Under MPI every rank takes part in both agreements, whatever it found:
  // nothing returns before the first.
  if (!this->AgreeToRender(input, request))
  {
    return 0;
  }
  this->LastFailure.reset();
  const int* extent = request.Extent.data();
  this->LastErrorText.clear();
  this->LastScatteredLightShares = 0;
  this->LastLightFieldShares = 0;
  this->LastMarchShares = 0;
  vtkInformation* inputInformation = inputVector[0]->GetInformationObject(0);
  RenderOutcome outcome =
    this->GatherVolume(input, inputInformation) ? RenderOutcome::Rendered : RenderOutcome::Failed;
  // This rank's piece of the image (the whole image where the ranks march
  // together), resolved once for the shared solve and the frame; none where it is empty.
  std::optional<opal::ResolvedFrame> piece;
  const bool empty = extent[1] < extent[0] || extent[3] < extent[2];
  if (this->MarchesShared())
  {
    piece = this->ResolvePiece(inputInformation, input, outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()));
  }
  else if (!empty)
  {
    piece = this->ResolvePiece(inputInformation, input, extent);
  }
  outcome = this->ShareBeforeFrame(outcome, piece ? &*piece : nullptr, input);
  if (this->MarchesShared())
  {
    outcome = this->RenderShared(outcome, *piece, empty ? nullptr : extent, output);
  }
  else if (outcome == RenderOutcome::Rendered && !piece)
  {
    output->Initialize();
  }
  else if (outcome == RenderOutcome::Rendered)
  {
    outcome = this->RenderExtent(*piece, input, output);
  }
  outcome = this->AgreeOnOutcome(outcome);
  if (outcome != RenderOutcome::Rendered)
  {
    output->Initialize(); // no rank keeps its piece of an image another failed
  }
  if (outcome == RenderOutcome::Failed)
  {
    this->LastFailure = request;
  }
  this->NoteMediumLayers(outcome == RenderOutcome::Rendered ? input : nullptr);
  return outcome == RenderOutcome::Rendered ? 1 : 0;
}

void vtkOpalSpectralRender::NoteMediumLayers(vtkImageData* input)
{
  vtkImageData* volume = input ? this->VolumeOf(input) : nullptr;
  std::pair<int, int> gathered{ 0, 0 }, device{ 0, 0 };
  if (this->HoldsUploadedVolume(volume))
  {
    const vtkOpalRenderInput::MediumPiece* medium = this->Gathered.Medium();
    gathered = medium ? medium->Held.Layers : std::make_pair(0, volume->GetDimensions()[2]);
    device = this->RenderSession->heldMediumLayers();
  }
  this->LastGatheredLayers[0] = gathered.first;
  this->LastGatheredLayers[1] = gathered.second;
  this->LastMediumLayers[0] = device.first;
  this->LastMediumLayers[1] = device.second;
}

bool vtkOpalSpectralRender::GatherVolume(vtkImageData* input, vtkInformation* inputInformation)
{
  const auto start = std::chrono::steady_clock::now();
  const bool held = this->HoldsUploadedVolume(this->VolumeOf(input)) && this->MediumServes(this->MarchesShared());
  const std::string error =
    this->Gathered.Update(this->Controller, input, inputInformation, !held, this->PieceHeld(this->MarchesShared()));
  this->LastGatherSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!error.empty())
  {
    this->SayError(error);
  }
  return error.empty();
}

vtkImageData* vtkOpalSpectralRender::VolumeOf(vtkImageData* input) const
{
  return this->Gathered.Of(this->Controller, input);
}

std::string vtkOpalSpectralRender::SettingsText() const
{
  std::string text = "PresetPlacement " + std::to_string(this->PresetPlacement ? 1 : 0) + "\n" +
    "ShareMarch " + std::to_string(this->ShareMarch ? 1 : 0) + "\n";
  const opal::RenderParameters p = this->GetRenderParameters();
  for (const auto& row : opal::renderParameterRows())
  {
    text += vtkOpalRankAgreement::SettingsLine(row.Name, row.Get(p));
  }
  return text;
}

bool vtkOpalSpectralRender::AgreeToRender(vtkImageData* input, const FailedRequest& request)
{
  namespace agreement = vtkOpalRankAgreement;
  agreement::RankView mine{ this->SettingsText(), RankReady, {} };
  if (this->LastFailure == request)
  {
    // A failed request leaves the output without the requested extent, so the
    // pipeline asks again at every update (a view: at every frame): the same
    // request fails at once, having said why, until the input or a setting changes.
    mine.Code = RankRepeated;
  }
  else if (!this->ReportedError.empty())
  {
    // The information request failed and said why (ParaView asks for data regardless).
    mine.Code = RankFailed;
    mine.Message = this->ReportedError;
  }
  else if (!input)
  {
    mine.Code = RankFailed;
    mine.Message = "The input is not image data; connect an Opal Volume.";
    vtkErrorMacro(<< mine.Message);
  }
  const vtkOpalRankWait::Naming naming("the ranks' agreement before the render");
  const std::vector<agreement::RankView> views = agreement::Gather(this->Controller, mine);
  const int failed = agreement::FirstWith(views, RankFailed);
  const std::string disagreement = failed < 0 ? agreement::SettingsDisagreement(views) : std::string();
  bool allRepeated = true;
  for (const agreement::RankView& view : views)
  {
    allRepeated = allRepeated && view.Code == RankRepeated;
  }
  if (failed < 0 && disagreement.empty())
  {
    return !allRepeated;
  }
  // Said once: by a rank that had not failed this request already.
  if (mine.Code == RankReady)
  {
    if (failed >= 0)
    {
      vtkErrorMacro("Rank " << failed << " of " << views.size() << " cannot render: "
                            << withoutFullStop(views[failed].Message) << "; no rank renders.");
    }
    else
    {
      vtkErrorMacro(<< disagreement);
    }
  }
  this->LastFailure = request; // on every rank alike
  return false;
}

vtkOpalSpectralRender::RenderOutcome vtkOpalSpectralRender::AgreeOnOutcome(RenderOutcome mine)
{
  namespace agreement = vtkOpalRankAgreement;
  const vtkOpalRankWait::Naming naming("the ranks' agreement after the render");
  const std::vector<agreement::RankView> views =
    agreement::Gather(this->Controller, { {}, static_cast<int>(mine), this->LastErrorText });
  // The worst outcome over the ranks, which every rank returns: a failure, a
  // lost device (the rank that lost it has said so and dropped it), an abort.
  for (const RenderOutcome worst : { RenderOutcome::Failed, RenderOutcome::DeviceLost, RenderOutcome::Aborted })
  {
    const int rank = agreement::FirstWith(views, static_cast<int>(worst));
    if (rank < 0)
    {
      continue;
    }
    if (mine == RenderOutcome::Rendered && worst != RenderOutcome::Aborted)
    {
      vtkErrorMacro("Rank " << rank << " of " << views.size() << " could not render its piece: "
                            << withoutFullStop(views[rank].Message) << "; no rank outputs its piece of the image.");
    }
    return worst;
  }
  return mine;
}

void vtkOpalSpectralRender::SayError(const std::string& message)
{
  this->LastErrorText = message;
  vtkErrorMacro(<< message);
}

vtkOpalSpectralRender::RenderOutcome vtkOpalSpectralRender::Guarded(const std::function<RenderOutcome()>& work)
{
  try
  {
    return work();
  }
  catch (const opal::DeviceLostError& e)
  {
    this->DropLostDevice(e);
    return RenderOutcome::DeviceLost;
  }
  catch (const opal::NoVulkanDeviceError& e)
  {
    this->SayError(std::string("No Vulkan device: ") + e.what());
  }
  catch (const std::exception& e)
  {
    this->SayError(e.what());
  }
  return RenderOutcome::Failed;
}

std::function<bool(double)> vtkOpalSpectralRender::RequestProgress()
{
  return [this](double fraction) {
    this->UpdateProgress(fraction);
    return !this->GetAbortExecute();
  };
}

opal::ResolvedFrame vtkOpalSpectralRender::ResolvePiece(
  vtkInformation* inputInformation, vtkImageData* input, const int extent[6]) const
{
  // The requested rows and columns (VTK's bottom-up rows to the renderer's top-down).
  opal::ResolvedFrame resolved = this->GetResolvedFrame(inputInformation, input);
  opal::RenderParameters& p = resolved.Parameters;
  p.ImageRegion = { extent[0], p.ImageSize[1] - 1 - extent[3], extent[1] - extent[0] + 1, extent[3] - extent[2] + 1 };
  return resolved;
}

vtkOpalSpectralRender::RenderOutcome vtkOpalSpectralRender::ShareBeforeFrame(
  RenderOutcome sofar, const opal::ResolvedFrame* piece, vtkImageData* input)
{
  if (vtkOpalRankAgreement::Ranks(this->Controller) < 2)
  {
    return sofar;
  }
  const RenderOutcome uploaded = sofar == RenderOutcome::Rendered && piece
    ? this->Guarded([&] {
        return this->UploadVolume(this->VolumeOf(input), this->MarchesShared()) ? sofar : RenderOutcome::Failed;
      })
    : sofar;
  // Each step is called by every rank whatever the one before left it with:
  // with this rank's session and frame where it is ready, and whether it
  // has failed the request already. A rank that aborted its share aborts
  // the request on every rank (said by none). `shares`, where given, keeps
  // how many ranks shared the step.
  using Step = std::function<vtkOpalRankShares::Result(opal::RenderSession*, bool, const opal::ResolvedFrame&)>;
  const auto share = [&](RenderOutcome before, const Step& step, int* shares) {
    const bool ready = before == RenderOutcome::Rendered && piece;
    return this->Guarded([&] {
      const vtkOpalRankShares::Result shared = step(ready ? this->RenderSession.get() : nullptr,
        before != RenderOutcome::Rendered, ready ? *piece : opal::ResolvedFrame{});
      if (shares)
      {
        *shares = shared.Shares;
      }
      return shared.Aborted ? RenderOutcome::Aborted : before;
    });
  };
  const auto aborted = [this] { return this->GetAbortExecute() != 0; };
  const RenderOutcome lit = share(
    uploaded,
    [&](opal::RenderSession* session, bool failed, const opal::ResolvedFrame& frame) {
      return vtkOpalSharedLightField::March(this->Controller, session, failed, frame, this->RequestProgress(), aborted);
    },
    &this->LastLightFieldShares);
  const RenderOutcome solved = share(
    lit,
    [&](opal::RenderSession* session, bool failed, const opal::ResolvedFrame& frame) {
      return vtkOpalSharedScatteredLight::Solve(this->Controller, session, failed, frame, this->RequestProgress(), aborted);
    },
    &this->LastScatteredLightShares);
  return share(
    solved,
    [&](opal::RenderSession* session, bool failed, const opal::ResolvedFrame& frame) {
      return vtkOpalSharedScatteredLight::WriteField(this->Controller, session, failed, frame, aborted);
    },
    nullptr);
}

vtkOpalSpectralRender::RenderOutcome vtkOpalSpectralRender::RenderExtent(
  const opal::ResolvedFrame& piece, vtkImageData* input, vtkImageData* output)
{
  return this->Guarded([&] {
    if (!this->UploadVolume(this->VolumeOf(input)))
    {
      return RenderOutcome::Failed;
    }
    const opal::RenderFrame frame = this->Session().render(piece, this->RequestProgress());
    this->NoteStepsAlone(frame);
    if (this->Publish(frame, output))
    {
      return RenderOutcome::Rendered;
    }
    // An aborted frame was not a failure of its input: asked for again, it renders.
    return frame.Status == opal::FrameStatus::Aborted ? RenderOutcome::Aborted : RenderOutcome::Failed;
  });
}

void vtkOpalSpectralRender::NoteStepsAlone(const opal::RenderFrame& frame)
{
  if (frame.Ran.ScatteredLight && this->LastScatteredLightShares == 0)
  {
    this->LastScatteredLightShares = 1; // solved alone, in the frame
  }
  if (frame.Ran.LightPass && this->LastLightFieldShares == 0)
  {
    this->LastLightFieldShares = 1; // marched or swept alone, in the frame
  }
}

bool vtkOpalSpectralRender::MarchesShared() const
{
  return this->ShareMarch && vtkOpalRankAgreement::Ranks(this->Controller) >= 2;
}

int vtkOpalSpectralRender::MostOverSharingRanks(int value)
{
  const vtkOpalRankWait::Naming naming("the live view's ranks' agreement on a frame");
  return this->MarchesShared() ? vtkOpalRankAgreement::MostOverRanks(this->Controller, value) : value;
}

vtkOpalSpectralRender::RenderOutcome vtkOpalSpectralRender::RenderShared(
  RenderOutcome sofar, const opal::ResolvedFrame& whole, const int extent[6], vtkImageData* output)
{
  std::optional<opal::RenderFrame> rendered;
  const RenderOutcome shared = this->Guarded([&] {
    const bool ready = sofar == RenderOutcome::Rendered;
    const vtkOpalRankShares::Result result = vtkOpalSharedMarch::Render(this->Controller,
      ready ? this->RenderSession.get() : nullptr, !ready, whole, this->RequestProgress(),
      [this] { return this->GetAbortExecute() != 0; }, rendered);
    this->LastMarchShares = result.Shares;
    return result.Aborted ? RenderOutcome::Aborted : sofar;
  });
  // No frame: a rank failed or aborted before (every rank's request then ends so, AgreeOnOutcome).
  if (shared != RenderOutcome::Rendered || !rendered)
  {
    return shared;
  }
  this->NoteStepsAlone(*rendered);
  if (!this->Publish(*rendered, output))
  {
    return rendered->Status == opal::FrameStatus::Aborted ? RenderOutcome::Aborted : RenderOutcome::Failed;
  }
  if (!extent)
  {
    output->Initialize();
  }
  else
  {
    output->Crop(extent);
  }
  return RenderOutcome::Rendered;
}

bool vtkOpalSpectralRender::Publish(const opal::RenderFrame& frame, vtkImageData* output)
{
  const std::vector<std::string> messages = this->Session().context().validationMessages();
  this->ValidationMessages = static_cast<int>(messages.size());
  if (!messages.empty())
  {
    // With OPAL_VULKAN_VALIDATION set, what the layer says is a bug: shown, and the request fails.
    this->SayError("The Vulkan validation layer reported " + std::to_string(messages.size()) +
      " message(s); the first: " + messages.front());
    return false;
  }
  if (frame.Status == opal::FrameStatus::Aborted)
  {
    output->Initialize();
    return false;
  }
  if (!frame.Image.Warning.empty())
  {
    vtkWarningMacro(<< frame.Image.Warning);
  }
  vtkOpalRenderOutput::Fill(frame.Image, this->Session().context().deviceName(), output);
  return true;
}

bool vtkOpalSpectralRender::StartBackgroundFrame(const opal::RenderParameters& parameters)
{
  this->CancelBackgroundFrame();
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!input || !this->VolumeOf(input))
  {
    // Under MPI the whole volume exists only once a data request has gathered it.
    vtkErrorMacro("The render has no input to render in the background; update it first.");
    return false;
  }
  const opal::ResolvedFrame frame = this->Resolve(parameters, this->GetInputInformation(0, 0), input);
  if (!frame.Error.empty())
  {
    vtkErrorMacro(<< frame.Error);
    return false;
  }
  try
  {
    if (!this->UploadVolume(this->VolumeOf(input)))
    {
      return false;
    }
    this->Session().startFrame(frame); // the session's own worker (the frame ticket)
    return true;
  }
  catch (const opal::DeviceLostError& e)
  {
    this->DropLostDevice(e);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
  }
  return false;
}

bool vtkOpalSpectralRender::IsEyeInsideOpal()
{
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  // Only the volume uploaded: an input the render has not read yet is the render's to report on.
  return this->HoldsUploadedVolume(this->VolumeOf(input)) &&
    this->RenderSession->eyeInsideOpal(this->GetResolvedFrame(this->GetInputInformation(0, 0), input));
}

int vtkOpalSpectralRender::GetBackgroundFrameState() const
{
  return this->RenderSession ? static_cast<int>(this->RenderSession->backgroundState()) : 0;
}

double vtkOpalSpectralRender::GetBackgroundFrameProgress() const
{
  return this->GetBackgroundFrameState() == 1 ? this->RenderSession->backgroundProgress() : 0.0;
}

bool vtkOpalSpectralRender::TakeBackgroundFrame(vtkImageData* image)
{
  try
  {
    const std::optional<opal::RenderFrame> frame =
      this->RenderSession ? this->RenderSession->takeFrame() : std::nullopt;
    return frame && this->Publish(*frame, image);
  }
  catch (const opal::DeviceLostError& e)
  {
    this->DropLostDevice(e); // the worker's frame, rethrown by takeFrame
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
  }
  return false;
}

void vtkOpalSpectralRender::CancelBackgroundFrame()
{
  if (this->RenderSession)
  {
    this->RenderSession->cancelFrame();
  }
}

int vtkOpalSpectralRender::GetNumberOfCompletedBackgroundFrames() const
{
  return this->EndedSessionFrames[0] + (this->RenderSession ? this->RenderSession->completedBackgroundFrames() : 0);
}

int vtkOpalSpectralRender::GetNumberOfAbandonedBackgroundFrames() const
{
  return this->EndedSessionFrames[1] + (this->RenderSession ? this->RenderSession->abandonedBackgroundFrames() : 0);
}

void vtkOpalSpectralRender::EndSession()
{
  if (this->RenderSession)
  {
    this->RenderSession->cancelFrame();
    this->EndedSessionFrames[0] += this->RenderSession->completedBackgroundFrames();
    this->EndedSessionFrames[1] += this->RenderSession->abandonedBackgroundFrames();
  }
  this->RenderSession.reset();
  this->UploadedVolume = nullptr;
}

void vtkOpalSpectralRender::DropLostDevice(const opal::DeviceLostError& error)
{
  this->EndSession();
  this->SayError(std::string(error.what()) + "; the next render creates a new device");
  // The filter's state changed (it has no device): a live view that
  // remembers a failed update by the filter's MTime asks again.
  this->Modified();
}

void vtkOpalSpectralRender::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  OPAL_RENDER_PARAMETERS(OPAL_VTK_PRINT)
  vtkOpalArrayCopy::print(os, indent, "PresetPlacement", this->PresetPlacement);
  vtkOpalArrayCopy::print(os, indent, "DeviceIndex", this->DeviceIndex);
  vtkOpalArrayCopy::print(os, indent, "DeviceMemoryLimit", this->DeviceMemoryLimit);
  vtkOpalArrayCopy::print(os, indent, "ShareMarch", this->ShareMarch);
  os << indent << "Controller: " << this->Controller << "\n";
}
