/**
 * @class vtkOpalSpectralRender
 * @brief Spectral render of an opal volume on Vulkan compute.
 *
 * Input: the volume of vtkOpalSource (point arrays ScatteringCoefficient,
 * DomainId, SurfaceDistance; the domain table DomainNormal and
 * DomainParticleDiameter in its field data). Output: a 2-D image
 * (rows bottom to top, as VTK images go) with point arrays RGB (uint8 x 3,
 * sRGB), Radiance (linear sRGB), XYZ, DominantBraggWavelength (nm),
 * Depth (mm) and, with WriteSpectrum on, Spectrum (one value per wavelength;
 * the wavelengths are in the field data array Wavelengths).
 *
 * The render follows the paper (§6) with docs/design.md §4's amendments: the light
 * optical depth is one scalar field per light position; the view ray refracts
 * at the smooth surface and crosses the voxels by 3-D DDA, gathering Rayleigh
 * single scattering and Bragg-Snell diffraction once per domain crossing.
 *
 * The output can be produced in pieces: each piece renders its rows from the
 * whole input volume, so pieces under MPI equal the one-process image.
 * With no Vulkan device the request fails with an error saying so.
 * A data request that failed (and said why) fails again at once, without a
 * second message or render, while the input, its version, the settings and
 * the extent are the same.
 *
 * By default the settings a volume implies come from it (a vtkOpalSource
 * records them in its output information, a saved volume in its field data):
 * ImageSize 0 x 0 takes the preset's image size (640 x 480 for custom),
 * RefractiveIndex 0 the model's, and unless PresetPlacement is off the
 * preset's placement of the stone (fig13: 5 degrees about x) comes before
 * ModelRotation and, while BraggModel and LatticePlanes are the paper's, a
 * kind of opal's Bragg model and planes are used.
 * (ParaView's proxy fills ImageSize and ModelRotation with the upstream
 * preset's values and turns PresetPlacement off, so its panel shows them:
 * docs/design.md §2.8.)
 *
 * The filter keeps a render session (docs/design.md §5): the volume stays on
 * the device while the input is unchanged, and the light field while the
 * light, the rotation and the refractive index are, so a new camera re-renders
 * without upload or light pass. A device lost (VK_ERROR_DEVICE_LOST) ends
 * the session: that request fails with one error naming it, and the next
 * creates a new device and uploads the volume again.
 *
 * A frame can also be rendered in the background while the caller goes on
 * (StartBackgroundFrame; the live view's final frames, docs/design.md §5.2):
 * the render session's frame ticket, on the session's own worker thread,
 * which touches no VTK object. Every other use of the session (an update, a
 * new background frame, a new device, the filter's end) first cancels the
 * frame and waits for it, which stops at its next check (between light-pass
 * slabs or march tiles).
 */
#pragma once

#include "OpalRenderParameterTable.h" // for OPAL_RENDER_PARAMETERS
#include "vtkImageAlgorithm.h"
#include "vtkOpalModule.h" // for export macro
#include "vtkOpalTableMacros.h" // for OPAL_VTK_SET_GET, OPAL_VTK_MEMBER
#include "vtkOpalVolumePieces.h" // for the gathered volume

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

class vtkMultiProcessController;

namespace opal
{
struct RenderFrame;
struct RenderParameters;
struct ResolvedFrame;
class RenderSession;
class DeviceLostError;
}

class vtkImageData;

class VTKOPAL_EXPORT vtkOpalSpectralRender : public vtkImageAlgorithm
{
public:
  static vtkOpalSpectralRender* New();
  vtkTypeMacro(vtkOpalSpectralRender, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Every render parameter of opal::RenderParameters, one Set/Get pair each
  /// (booleans also XOn/XOff), generated from OPAL_RENDER_PARAMETERS
  /// (OpalRenderParameterTable.h), which gives each one's default, range and
  /// meaning. ImageSize 0 x 0 and RefractiveIndex 0, the defaults here, take
  /// the volume's (its preset's image size, 640 x 480 for custom; the model's
  /// index).
  OPAL_RENDER_PARAMETERS(OPAL_VTK_SET_GET)
  ///@}
  /// Whether the volume's preset decides its render settings: its placement
  /// (fig13: 5 degrees about x) turns the stone before ModelRotation, and
  /// while BraggModel and LatticePlanes are their defaults (paper, 111) a
  /// kind of opal's (black-opal: coupled-wave, fcc) are used instead
  /// (opal::renderHints). Default on; off where the properties already hold
  /// the preset's (as ParaView's proxy fills them in), or to render a kind of
  /// opal with the paper's model.
  vtkSetMacro(PresetPlacement, bool);
  vtkGetMacro(PresetPlacement, bool);
  vtkBooleanMacro(PresetPlacement, bool);
  /// Vulkan device index; -1 picks OPAL_VULKAN_DEVICE or the best device. Default -1.
  vtkSetMacro(DeviceIndex, int);
  vtkGetMacro(DeviceIndex, int);
  /// Limit on device memory in MB (0: none), to test or to protect a small device.
  vtkSetMacro(DeviceMemoryLimit, int);
  vtkGetMacro(DeviceMemoryLimit, int);
  /// Under MPI, each rank marches the view rays only in its piece of the
  /// volume's layers z, handing those that leave it to the other ranks
  /// between rounds (docs/design.md §8.1); every rank renders the whole image
  /// and outputs its piece, its device holding only its piece of the light
  /// fields and the medium (its cells and SurfaceDistance). Off (default): each rank renders its
  /// piece of the image from the whole volume. With one process it changes nothing.
  vtkSetMacro(ShareMarch, bool);
  vtkGetMacro(ShareMarch, bool);
  vtkBooleanMacro(ShareMarch, bool);
  /// The ranks of one render (docs/design.md §8.1), as VTK's parallel filters
  /// take them: each asks for its piece of the volume, they gather what the
  /// render reads and agree before and after it. Default: the global
  /// controller; nullptr (or one process) renders alone from the whole volume.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// Seconds the last data request spent gathering the ranks' pieces into the
  /// whole volume (docs/design.md §8.1): where no rank's piece had changed,
  /// only the ranks' check of that; ~0 with one process.
  vtkGetMacro(LastGatherSeconds, double);
  /// How many ranks traced the every-order field (ScatteringOrders all) that
  /// this rank's last data request solved (docs/design.md §8.1): under MPI the
  /// ranks share the photons, one process solves alone (1); 0 where the
  /// request solved none (single scattering, or a field held from before).
  vtkGetMacro(LastScatteredLightShares, int);
  /// How many ranks computed the light field that this rank's last data
  /// request used (docs/design.md §8.1): under MPI the ranks share the march
  /// per voxel of a light low or to the side; 1 where the frame computed it
  /// alone (a light above is swept by each rank alone); 0 where the request
  /// computed none (a light field held from before served).
  vtkGetMacro(LastLightFieldShares, int);
  /// How many ranks marched the view rays of this rank's last data request
  /// together (ShareMarch; docs/design.md §8.1); 0 where it marched alone.
  vtkGetMacro(LastMarchShares, int);
  /// The layers z [first, end) of the volume's medium (its arrays but
  /// SurfaceDistance) that this rank's last data request gathered on the host
  /// and that its device held for the render (docs/design.md §8.1): all of
  /// them with one process or a march unshared; under ShareMarch the rank's
  /// piece with the halo its reads need. {0, 0} where it rendered none.
  vtkGetVector2Macro(LastGatheredLayers, int);
  vtkGetVector2Macro(LastMediumLayers, int);
  /// Where the ranks march shared (ShareMarch under MPI), collective over the
  /// controller's ranks: the largest of their `value`s; `value` itself
  /// otherwise. A live view's ranks so agree on what each finds alone and
  /// every frame of theirs must share: a preview's PreviewScale (each rank's
  /// budget measures its own frames) and whether the eye is inside the stone
  /// (a rank whose volume a failed frame dropped cannot tell).
  int MostOverSharingRanks(int value);

  /// The parameters as set on the filter (ImageSize and RefractiveIndex may
  /// be 0: the volume's; PresetRotation is the volume's and not a property).
  opal::RenderParameters GetRenderParameters() const;
  /// Sets every render parameter at once (PresetRotation is ignored: it is the volume's).
  void SetRenderParameters(const opal::RenderParameters& parameters);

  /// The frame a render of this input renders (opal::resolveFrame): the
  /// properties with the volume's settings where ImageSize and RefractiveIndex
  /// are 0 and the preset's placement (from the input's pipeline information;
  /// without it, the refractive index and placement from the input volume's
  /// field data), the quality's reductions applied and the preview kept.
  opal::ResolvedFrame GetResolvedFrame(vtkInformation* inputInformation, vtkImageData* input = nullptr) const;

  /// Validation-layer messages of the last render (OPAL_VULKAN_VALIDATION=1).
  int GetNumberOfValidationMessages() const;

  /// Starts rendering `parameters` (as set on the filter; resolved against the
  /// input like an update's) on a worker thread, from the input of the last
  /// update, and returns. A background frame still running is cancelled first;
  /// the volume is uploaded here if the session lacks it. False, with an
  /// error, if the frame cannot start (bad settings, no input).
  bool StartBackgroundFrame(const opal::RenderParameters& parameters);
  /// Whether EyePosition is inside the opal of the input (which a render
  /// refuses), as the render would place it; false until the input's volume
  /// is uploaded (by a render).
  bool IsEyeInsideOpal();
  /// 0 none, 1 running, 2 finished (TakeBackgroundFrame gives it).
  int GetBackgroundFrameState() const;
  /// The running background frame's fraction done, 0-1 (0 when none runs).
  double GetBackgroundFrameProgress() const;
  /// Fills `image` with the finished background frame as an update would fill
  /// the output; false if none has finished, or it failed (said in an error).
  bool TakeBackgroundFrame(vtkImageData* image);
  /// Cancels a running background frame and waits for it to stop; a finished
  /// one not taken is dropped.
  void CancelBackgroundFrame();
  ///@{
  /// Background frames that completed, and that were cancelled before they
  /// completed (abandoned), since the filter was made (for tests).
  int GetNumberOfCompletedBackgroundFrames() const;
  int GetNumberOfAbandonedBackgroundFrames() const;
  ///@}

protected:
  vtkOpalSpectralRender();
  ~vtkOpalSpectralRender() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  OPAL_RENDER_PARAMETERS(OPAL_VTK_MEMBER)
  vtkMultiProcessController* Controller = nullptr;
  bool PresetPlacement = true;
  int DeviceIndex;
  int DeviceMemoryLimit;
  bool ShareMarch = false;

private:
  vtkOpalSpectralRender(const vtkOpalSpectralRender&) = delete;
  void operator=(const vtkOpalSpectralRender&) = delete;

  // The session for the current device settings, created on first use.
  opal::RenderSession& Session();
  // Uploads the input volume unless the session already holds this version
  // of it. Under MPI the gathered volume's arrays are released after the
  // upload (the device holds their values; docs/design.md §8.1): an upload
  // that needs them again fails, saying that the render's update gathers them.
  // `marchShared`: the frames that follow march shared by the ranks
  // (MarchesShared), whose light fields and medium the session then holds
  // by piece; a medium held by piece that the frames do not serve is
  // uploaded again (its arrays gathered again: GatherVolume, MediumServes).
  bool UploadVolume(vtkImageData* input, bool marchShared = false);
  // Whether a session exists for the current device settings (Session would keep it).
  bool HasSessionOfSettings() const;
  // Whether that session holds this version of `volume`.
  bool HoldsUploadedVolume(vtkImageData* volume) const;
  bool MediumServes(bool marchShared) const;
  std::pair<int, int> PieceHeld(bool marchShared) const;
  // `parameters` resolved against this input (GetResolvedFrame).
  opal::ResolvedFrame Resolve(
    const opal::RenderParameters& parameters, vtkInformation* inputInformation, vtkImageData* input) const;
  // A rendered frame into `output`; false, with an error, for validation-layer
  // messages or an aborted frame.
  bool Publish(const opal::RenderFrame& frame, vtkImageData* output);

  enum class RenderOutcome
  {
    Rendered,
    Failed, // said in an error
    Aborted,
    DeviceLost, // said in an error; not the request's failure: asked again, it renders on a new device
  };
  // `work`'s outcome, or the failure of the exception it threw, said in an
  // error (a lost device dropped, DropLostDevice).
  RenderOutcome Guarded(const std::function<RenderOutcome()>& work);
  // The data request's progress, false once it is asked to abort.
  std::function<bool(double)> RequestProgress();
  // The update extent's piece of the image, resolved against this input.
  opal::ResolvedFrame ResolvePiece(vtkInformation* inputInformation, vtkImageData* input, const int extent[6]) const;
  // Under MPI, collective, every rank between the gather and its frame:
  // the ranks that render a piece (nullptr: none; so far `sofar`) upload the
  // volume, and they share the light field (vtkOpalSharedLightField), then
  // every order's photon solve and the writing of its field per voxel
  // (vtkOpalSharedScatteredLight).
  RenderOutcome ShareBeforeFrame(RenderOutcome sofar, const opal::ResolvedFrame* piece, vtkImageData* input);
  // Renders this rank's piece of the image into `output`.
  RenderOutcome RenderExtent(const opal::ResolvedFrame& piece, vtkImageData* input, vtkImageData* output);
  // Whether the ranks march together (ShareMarch under MPI).
  bool MarchesShared() const;
  // Under MPI with ShareMarch, collective: every rank renders `whole` (the
  // whole image) with the march shared (vtkOpalSharedMarch; so far
  // `sofar`), and keeps `extent`, its piece, in `output` (nullptr: none).
  RenderOutcome RenderShared(
    RenderOutcome sofar, const opal::ResolvedFrame& whole, const int extent[6], vtkImageData* output);
  // What a frame computed alone that the ranks did not share before it.
  void NoteStepsAlone(const opal::RenderFrame& frame);

  // Ends the session (its background frame first), keeping its frame counts.
  void EndSession();
  // After VK_ERROR_DEVICE_LOST nothing made on the device is usable: the
  // session and the volume's upload go, said once in an error, and the next
  // request creates a new device.
  void DropLostDevice(const opal::DeviceLostError& error);
  // Completed and abandoned background frames of the sessions ended so far.
  int EndedSessionFrames[2] = { 0, 0 };

  std::unique_ptr<opal::RenderSession> RenderSession;
  int SessionDeviceIndex = -2;
  int SessionMemoryLimit = -1;
  vtkDataObject* UploadedVolume = nullptr; // identity and version of the volume on the device
  vtkMTimeType UploadedVolumeTime = 0;
  int ValidationMessages = 0;
  // The image's extent as the last good RequestInformation announced it
  // (empty before one): a failed request announces it again, so that no
  // consumer keeps an extent the filter never had (the input's, copied by
  // the executive) once the failure is fixed.
  int AnnouncedExtent[6] = { 0, -1, 0, -1, 0, -1 };
  // The settings' error last reported and the filter's modification time
  // then: ParaView asks for the information more than once per change, and
  // one bad setting is reported once.
  std::string ReportedError;
  vtkMTimeType ReportedErrorTime = 0;
  // The data request that failed last, and said why: the same input, in the
  // same version, with the same settings and extent fails again at once,
  // without a second message or render.
  struct FailedRequest
  {
    vtkDataObject* Input;
    vtkMTimeType InputTime;
    vtkMTimeType SettingsTime;
    std::array<int, 6> Extent;
    bool operator==(const FailedRequest& other) const
    {
      return this->Input == other.Input && this->InputTime == other.InputTime &&
        this->SettingsTime == other.SettingsTime && this->Extent == other.Extent;
    }
  };
  std::optional<FailedRequest> LastFailure;

  // Each rank's state for an exchange (vtkOpalRankAgreement), beside the outcomes.
  enum RankCode
  {
    RankReady = 0,
    RankRepeated = 1, // the request that failed last, asked again
    RankFailed = 2,   // said in an error
  };
  // The settings as every rank must have them: a line per parameter.
  std::string SettingsText() const;
  // The first agreement: false where this request must fail (said once, in
  // an error on every rank): a rank's information or input failed, the
  // ranks' settings differ, or every rank asks again for its last failure.
  bool AgreeToRender(vtkImageData* input, const FailedRequest& request);
  // The second: the ranks' worst outcome, which each rank returns (one that
  // rendered says which rank failed, and why).
  RenderOutcome AgreeOnOutcome(RenderOutcome mine);
  // Under MPI, collective: the whole volume gathered from the ranks' pieces
  // (vtkOpalVolumePieces), again where any rank's piece changed or a rank
  // whose device no longer holds it needs the released arrays; false, said
  // in an error, where the pieces differ or the whole does not fit.
  bool GatherVolume(vtkImageData* input, vtkInformation* inputInformation);
  // The volume the render reads for this input: the input itself with one
  // process, the gathered volume under MPI (nullptr before a data request
  // gathered it).
  vtkImageData* VolumeOf(vtkImageData* input) const;
  vtkOpalVolumePieces::GatheredVolume Gathered;
  double LastGatherSeconds = 0;
  int LastScatteredLightShares = 0;
  int LastLightFieldShares = 0;
  int LastMarchShares = 0;
  int LastGatheredLayers[2] = { 0, 0 };
  int LastMediumLayers[2] = { 0, 0 };
  // Records the layers of the medium gathered and held for `input` (LastGatheredLayers,
  // LastMediumLayers): none for nullptr (a request that did not render).
  void NoteMediumLayers(vtkImageData* input);
  // An error of the data request, kept for the outcome's agreement.
  void SayError(const std::string& message);
  std::string LastErrorText;
};
