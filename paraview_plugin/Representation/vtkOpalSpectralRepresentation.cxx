#include "vtkOpalSpectralRepresentation.h"

#include "OpalRenderParameters.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpalSpectralImageActor.h"
#include "vtkOpalSpectralRender.h"
#include "vtkOpalVolumePieces.h"
#include "vtkPVRenderView.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"

#include <string>

vtkStandardNewMacro(vtkOpalSpectralRepresentation);

namespace
{
// Process-wide: set by the GUI's plugin part in the GUI only (docs/design.md §5.2).
bool finalFramesInBackground = false;

// Whether the view renders for a screenshot. ParaView 5.11 keeps the getter
// protected; its address taken through a subclass is usable on any view.
struct ScreenshotFlag : vtkPVView
{
  static bool Of(vtkPVView* view) { return (view->*(&ScreenshotFlag::GetInCaptureScreenshot))(); }
};
} // namespace

void vtkOpalSpectralRepresentation::SetFinalFramesInBackground(bool background)
{
  finalFramesInBackground = background;
}

bool vtkOpalSpectralRepresentation::GetFinalFramesInBackground()
{
  return finalFramesInBackground;
}

vtkMTimeType vtkOpalSpectralRepresentation::GetReadyFinalFrame()
{
  return this->Actor->GetReadyFinalFrame();
}

int vtkOpalSpectralRepresentation::GetLastFrameQuality()
{
  return this->Actor->GetLastQuality();
}

int vtkOpalSpectralRepresentation::GetNumberOfCompletedFinalFrames()
{
  return this->Render->GetNumberOfCompletedBackgroundFrames();
}

int vtkOpalSpectralRepresentation::GetNumberOfAbandonedFinalFrames()
{
  return this->Render->GetNumberOfAbandonedBackgroundFrames();
}

vtkOpalSpectralRepresentation::vtkOpalSpectralRepresentation()
  : Gathered(std::make_unique<vtkOpalVolumePieces::GatheredVolume>())
{
  this->Actor->SetRender(this->Render);
  // The stone stays where the scene has it (its Domains, slices): no preset
  // placement (fig13's 5 degrees), only OpalModelRotation; the Bragg model as
  // the representation's properties say (ParaView fills in the preset's).
  this->Render->SetPresetPlacement(false);
  // Each rank draws the whole stone into its own view from the whole volume
  // gathered at the update (ParaView composites the views): its render stands
  // alone, and the view's frames on one rank never wait for another's
  // (docs/design.md §8.1).
  this->Render->SetController(nullptr);
}

void vtkOpalSpectralRepresentation::SetRenderSettings(vtkOpalSpectralRender* settings)
{
  this->Settings = settings;
  this->SettingsTime = 0;
  this->AppliedSettings.reset();
  this->Modified();
}

namespace
{
// The frame's own rows, which the view sets on the render at every frame.
bool isFramesOwn(const std::string& name)
{
  for (const char* own : { "ImageSize", "ImageRegion", "EyePosition", "FocalPoint", "ViewUp", "ViewAngle", "Quality",
         "PreviewScale", "WriteSpectrum" })
  {
    if (name == own)
    {
      return true;
    }
  }
  return false;
}
} // namespace

void vtkOpalSpectralRepresentation::ApplyRenderSettings()
{
  if (!this->Settings || this->Settings->GetMTime() <= this->SettingsTime)
  {
    return;
  }
  this->SettingsTime = this->Settings->GetMTime();
  const opal::RenderParameters settings = this->Settings->GetRenderParameters();
  opal::RenderParameters p = this->Render->GetRenderParameters();
  bool changed = false;
  // Only the rows that changed since the last copy, as a property push would:
  // the headlight's LightPosition stays the view's until OpalLightPosition changes.
  for (const opal::ParameterRow<opal::RenderParameters>& row : opal::renderParameterRows())
  {
    const bool moved = !this->AppliedSettings || row.Get(settings) != row.Get(*this->AppliedSettings);
    if (moved && !isFramesOwn(row.Name) && row.Get(settings) != row.Get(p))
    {
      row.Set(p, row.Get(settings));
      changed = true;
    }
  }
  this->AppliedSettings = std::make_unique<opal::RenderParameters>(settings);
  // Unchanged settings keep the render's MTime: its final frame stays valid.
  if (changed)
  {
    this->Render->SetRenderParameters(p);
  }
}

vtkOpalSpectralRepresentation::~vtkOpalSpectralRepresentation() = default;

int vtkOpalSpectralRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

// Each rank asks for its piece of the volume alone, as the render does
// (docs/design.md §8.1).
int vtkOpalSpectralRepresentation::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
  for (int i = 0; i < inputVector[0]->GetNumberOfInformationObjects(); ++i)
  {
    vtkOpalVolumePieces::AskForPiece(
      vtkMultiProcessController::GetGlobalController(), inputVector[0]->GetInformationObject(i));
  }
  return 1;
}

// Under MPI, collective (every rank's view updates together): the ranks'
// pieces gathered into the whole volume, again where any rank's piece changed.
// Its arrays are never released (needsArrays is moot): the representation
// starts its frames (and their uploads) outside any data request, where no
// rank may gather.
vtkImageData* vtkOpalSpectralRepresentation::WholeVolume(vtkImageData* piece, vtkInformation* pieceInformation)
{
  vtkMultiProcessController* ranks = vtkMultiProcessController::GetGlobalController();
  const std::string error = this->Gathered->Update(ranks, piece, pieceInformation, true);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
  }
  return this->Gathered->Of(ranks, piece);
}

int vtkOpalSpectralRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* piece = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[0], 0)
    : nullptr;
  vtkInformation* pieceInformation = piece ? inputVector[0]->GetInformationObject(0) : nullptr;
  if (piece && this->MarchesShared())
  {
    this->TakePiece(piece, pieceInformation);
  }
  else if (!this->TakeWholeVolume(piece, pieceInformation))
  {
    return 0; // the pieces were not gathered (said): the view keeps the stone it had
  }
  this->ApplyRenderSettings();
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

// A new volume only when the input changed: the render session then keeps
// the uploaded volume and the light field across property changes.
bool vtkOpalSpectralRepresentation::TakeWholeVolume(vtkImageData* piece, vtkInformation* pieceInformation)
{
  vtkImageData* input = piece ? this->WholeVolume(piece, pieceInformation) : nullptr;
  if (piece && !input)
  {
    return false;
  }
  if (input && this->HoldsVolume(input, false))
  {
    return true;
  }
  this->TakenVolume = { input ? input->GetMTime() : 0, false };
  this->Volume = vtkSmartPointer<vtkImageData>::New();
  if (input)
  {
    this->Volume->ShallowCopy(input);
  }
  this->PlaceStone(this->Volume->GetExtent(), this->Volume);
  this->PieceProducer->SetOutput(nullptr); // a piece held for a shared march would keep its arrays
  this->Render->SetController(nullptr);
  this->Render->SetShareMarch(false);
  this->Render->SetInputData(this->Volume);
  return true;
}

// The render gathers, in each frame's update (collective: the ranks render
// their views' frames together), what its device reads of the ranks' pieces.
void vtkOpalSpectralRepresentation::TakePiece(vtkImageData* piece, vtkInformation* pieceInformation)
{
  if (this->HoldsVolume(piece, true))
  {
    return;
  }
  this->Gathered = std::make_unique<vtkOpalVolumePieces::GatheredVolume>(); // the unshared frames' whole volume
  this->TakenVolume = { piece->GetMTime(), true };
  this->Volume = vtkSmartPointer<vtkImageData>::New();
  this->Volume->ShallowCopy(piece);
  int whole[6];
  pieceInformation->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  this->PlaceStone(whole, this->Volume);
  this->PieceProducer->SetOutput(this->Volume);
  this->PieceProducer->SetWholeExtent(whole);
  this->Render->SetController(vtkMultiProcessController::GetGlobalController());
  this->Render->SetShareMarch(true);
  this->Render->SetInputConnection(this->PieceProducer->GetOutputPort());
}

bool vtkOpalSpectralRepresentation::HoldsVolume(vtkImageData* input, bool asPiece) const
{
  return this->Volume && input->GetMTime() == this->TakenVolume.Time && this->TakenVolume.AsPiece == asPiece;
}

bool vtkOpalSpectralRepresentation::MarchesShared() const
{
  vtkMultiProcessController* ranks = vtkMultiProcessController::GetGlobalController();
  return this->ShareMarch && ranks && ranks->GetNumberOfProcesses() > 1;
}

// Voxel centres are the points: the stone's box reaches half a voxel further
// (an Opal volume's axes are the scene's: its direction matrix is the identity).
void vtkOpalSpectralRepresentation::PlaceStone(const int extent[6], vtkImageData* placed)
{
  const double* origin = placed->GetOrigin();
  const double* spacing = placed->GetSpacing();
  const bool empty = extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4];
  for (int a = 0; a < 3; ++a)
  {
    this->Bounds[2 * a] = empty ? 0 : origin[a] + spacing[a] * (extent[2 * a] - 0.5);
    this->Bounds[2 * a + 1] = empty ? -1 : origin[a] + spacing[a] * (extent[2 * a + 1] + 0.5);
  }
  this->Actor->SetStoneBounds(this->Bounds);
}

void vtkOpalSpectralRepresentation::SetShareMarch(int share)
{
  if (this->ShareMarch != (share != 0))
  {
    this->ShareMarch = share != 0;
    this->MarkModified(); // the view updates the representation again: its input changes
  }
}

int vtkOpalSpectralRepresentation::GetLastMarchShares()
{
  return this->Render->GetLastMarchShares();
}

int vtkOpalSpectralRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    // The camera's reset and clipping range include the stone; the frame is
    // drawn where the data is (the render server), never delivered.
    vtkPVRenderView::SetGeometryBounds(inInfo, this, this->Bounds);
    vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    this->ApplyRenderSettings(); // a setting changed since the update
    // A screenshot (a tiled one too) waits for its final frame.
    auto* view = vtkPVView::SafeDownCast(this->GetView());
    this->Actor->SetDeferFinalFrames(finalFramesInBackground && view && !ScreenshotFlag::Of(view));
  }
  return 1;
}

bool vtkOpalSpectralRepresentation::AddToView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->AddActor(this->Actor);
  return this->Superclass::AddToView(view);
}

bool vtkOpalSpectralRepresentation::RemoveFromView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  // The textures go with the window they were made in, which may close first.
  this->Actor->ReleaseGraphicsResources(renderView->GetRenderWindow());
  this->Actor->CancelFinalFrame();
  renderView->GetRenderer()->RemoveActor(this->Actor);
  return this->Superclass::RemoveFromView(view);
}

void vtkOpalSpectralRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(visible ? 1 : 0);
  if (!visible)
  {
    this->Actor->CancelFinalFrame();
  }
}

void vtkOpalSpectralRepresentation::SetHeadlight(int headlight)
{
  this->Actor->SetHeadlight(headlight != 0);
}

void vtkOpalSpectralRepresentation::SetQuality(int quality)
{
  this->Actor->SetStillQuality(quality);
}

void vtkOpalSpectralRepresentation::SetFrameBudget(double seconds)
{
  this->Actor->SetFrameBudget(seconds);
}

bool vtkOpalSpectralRepresentation::GetRefinementProgress(int& pass, int& passes, double& fraction)
{
  return this->Actor->GetRefinementProgress(pass, passes, fraction);
}

double vtkOpalSpectralRepresentation::GetRefinementProgressValue()
{
  int pass = 0, passes = 0;
  double fraction = 0;
  return this->GetRefinementProgress(pass, passes, fraction) ? pass - 1 + fraction : -1.0;
}

int vtkOpalSpectralRepresentation::GetLastPreviewScale()
{
  return this->Actor->GetLastPreviewScale();
}

vtkOpalSpectralRender* vtkOpalSpectralRepresentation::GetRender()
{
  return this->Render;
}

vtkOpalSpectralImageActor* vtkOpalSpectralRepresentation::GetActor()
{
  return this->Actor;
}

// Prints the actor's settings by their setters' names, and the render filter.
void vtkOpalSpectralRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Headlight: " << this->Actor->GetHeadlight() << "\n";
  os << indent << "Quality: " << this->Actor->GetStillQuality() << "\n";
  os << indent << "FrameBudget: " << this->Actor->GetFrameBudget() << "\n";
  os << indent << "ShareMarch: " << (this->ShareMarch ? 1 : 0) << "\n";
  os << indent << "Render:\n";
  this->Render->PrintSelf(os, indent.GetNextIndent());
}
