/**
 * @class vtkOpalSpectralRepresentation
 * @brief "Opal Spectral": the opal volume rendered spectrally from the render view's camera.
 *
 * A representation of an Opal Volume (its port 0) in ParaView's render view
 * (docs/design.md §5.2). Every time the view renders, the stone is rendered
 * from the view's own camera at the view's size by a vtkOpalSpectralRender
 * kept by this representation (its render session keeps the volume and, while
 * the light and the rotation hold still, the light field on the device), and
 * drawn with its depth by a vtkOpalSpectralImageActor, so rotating, panning or
 * zooming changes the play of colour and the domains, slices and axes mix
 * with the stone. While the view is dragged the frames are previews; the
 * still frame that follows has Quality. With FinalFramesInBackground on (the
 * GUI's plugin part sets it), a still render does not wait for a final frame:
 * it draws the preview, the final frame renders on a worker thread, and the
 * GUI renders the view again when GetReadyFinalFrame says it has finished;
 * screenshots always wait. Under MPI (pvserver, pvbatch) each rank asks its
 * input for its piece of the volume alone, the ranks gather the arrays the
 * render reads into the whole volume on every rank, and each rank renders the
 * whole stone from it; with ShareMarch the ranks march each frame's rays
 * together instead, each rank's device holding only its piece of the volume's
 * layers (docs/design.md §8.1).
 *
 * The optics are the render filter's settings, with its defaults
 * (opal::RenderParameters): RefractiveIndex, BraggBandwidth, DiffractionGain, BraggModel,
 * LatticePlanes, CoherentLayers, EnergyConservation,
 * BraggOrders, MosaicSpread, LightRadius, LightFalloffAtEntry, Exposure,
 * WavelengthStep and ModelRotation, forwarded to the filter. The light is a
 * headlight (the paper's set-up) or LightPosition.
 */
#pragma once

#include "vtkNew.h"
#include "vtkOpalRepresentationModule.h" // for export macro
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h"

#include <memory>

namespace opal
{
struct RenderParameters;
}
namespace vtkOpalVolumePieces
{
class GatheredVolume;
}

class vtkImageData;
class vtkInformation;
class vtkOpalSpectralImageActor;
class vtkOpalSpectralRender;
class vtkTrivialProducer;

class VTKOPALREPRESENTATION_EXPORT vtkOpalSpectralRepresentation : public vtkPVDataRepresentation
{
public:
  static vtkOpalSpectralRepresentation* New();
  vtkTypeMacro(vtkOpalSpectralRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  /// The light: at the eye (Headlight 1, default) or at the render filter's
  /// LightPosition (mm).
  void SetHeadlight(int headlight);

  /// Quality of still frames: 0 final (default), 1 preview. Dragging always previews.
  void SetQuality(int quality);

  /// Seconds a frame should take while the view is dragged (default 0.1): the
  /// previews' resolution follows the measured cost of the last ones. 0: half
  /// the pixels each way, whatever they cost.
  void SetFrameBudget(double seconds);

  /// The refinement passes under way in the background (docs/design.md §5.2):
  /// the pass (1-based), their number and the pass's fraction done; false if none runs.
  bool GetRefinementProgress(int& pass, int& passes, double& fraction);

  /// The same as one number, for tests: passes done plus the running one's
  /// fraction (0 at the first pass's start), -1 if none runs.
  double GetRefinementProgressValue();

  /// The last preview's PreviewScale (its pixels: 1/scale of the width and height), for tests.
  int GetLastPreviewScale();

  /// Under MPI (pvserver, pvbatch): on, the ranks march every frame's view
  /// rays and walks to the light together, each rank's device holding only
  /// its piece of the light fields and the medium, as Opal Spectral Render's
  /// ShareMarch; every frame is then collective (the ranks render each frame
  /// together, as ParaView's views do) and the ranks' previews take the
  /// coarsest of their budgets' scales. Off (default): each rank renders the
  /// whole stone from the whole volume gathered at the update. The picture is
  /// the same either way; with one process it changes nothing.
  void SetShareMarch(int share);
  /// How many ranks marched the last frame together (0: each alone), for tests.
  int GetLastMarchShares();

  /// Where the render's settings come from: an Opal Spectral Render whose
  /// properties (ParaView passes its SubProxy here and exposes that proxy's
  /// properties on the representation) are copied into the filter that
  /// renders each frame before it renders, except the frame's own (camera,
  /// image size, quality), which the view sets. The render keeps
  /// PresetPlacement off: the stone stays where the scene has it.
  void SetRenderSettings(vtkOpalSpectralRender* settings);

  ///@{
  /// Still final frames rendered on a worker thread, not waited for, in every
  /// representation of this process (docs/design.md §5.2). Off by default
  /// (pvpython, pvbatch, pvserver: a render or a screenshot has its final
  /// frame); the GUI's plugin part turns it on, and renders a view again
  /// when one of its representations has a final frame ready.
  static void SetFinalFramesInBackground(bool background);
  static bool GetFinalFramesInBackground();
  ///@}

  /// A final frame finished in the background and not yet drawn: its id (> 0,
  /// the same until drawn or dropped), or 0. The view should render again.
  vtkMTimeType GetReadyFinalFrame();

  ///@{
  /// For tests: the quality of the frame last drawn (0 final, 1 preview, -1
  /// none), and the background final frames completed and abandoned.
  int GetLastFrameQuality();
  int GetNumberOfCompletedFinalFrames();
  int GetNumberOfAbandonedFinalFrames();
  ///@}

  /// The filter that renders each frame (for tests and scripts).
  vtkOpalSpectralRender* GetRender();
  /// The actor that draws it.
  vtkOpalSpectralImageActor* GetActor();

protected:
  vtkOpalSpectralRepresentation();
  ~vtkOpalSpectralRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  vtkOpalSpectralRepresentation(const vtkOpalSpectralRepresentation&) = delete;
  void operator=(const vtkOpalSpectralRepresentation&) = delete;

  // The whole volume of the input's piece (this rank's under MPI); nullptr
  // where the ranks' pieces could not be gathered (said in an error).
  vtkImageData* WholeVolume(vtkImageData* piece, vtkInformation* pieceInformation);
  // Copies the settings' rows into Render if they changed since the last copy.
  void ApplyRenderSettings();
  // Whether the ranks march shared (ShareMarch under MPI).
  bool MarchesShared() const;
  // Whether Volume holds `input` as it is now, taken as a piece (or whole).
  bool HoldsVolume(vtkImageData* input, bool asPiece) const;
  // The render's input, its own rendering alone: the whole volume gathered
  // from the ranks' pieces (the piece itself with one process). False where
  // the pieces could not be gathered (said).
  bool TakeWholeVolume(vtkImageData* piece, vtkInformation* pieceInformation);
  // The render's input where the ranks march shared: this rank's piece,
  // announced with the whole extent, the render gathering what its device
  // reads in each frame's update.
  void TakePiece(vtkImageData* piece, vtkInformation* pieceInformation);
  // Bounds, and the actor's, from the extent of the stone's voxel centres
  // placed as `placed`.
  void PlaceStone(const int extent[6], vtkImageData* placed);

  vtkNew<vtkOpalSpectralRender> Render;
  vtkSmartPointer<vtkOpalSpectralRender> Settings;
  vtkMTimeType SettingsTime = 0; // the settings' MTime at the last copy
  std::unique_ptr<opal::RenderParameters> AppliedSettings; // the settings as last copied
  vtkNew<vtkOpalSpectralImageActor> Actor;
  std::unique_ptr<vtkOpalVolumePieces::GatheredVolume> Gathered; // under MPI, from the ranks' pieces
  vtkSmartPointer<vtkImageData> Volume;
  // What Volume was taken from: the whole volume's (or the piece's) MTime
  // then, and whether it is this rank's piece, fed through PieceProducer.
  struct
  {
    vtkMTimeType Time = 0;
    bool AsPiece = false;
  } TakenVolume;
  bool ShareMarch = false;
  vtkNew<vtkTrivialProducer> PieceProducer;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
};
