/**
 * @class vtkOpalSpectralImageActor
 * @brief Draws the spectral render of an opal from the renderer's own camera, with depth.
 *
 * At each opaque pass it renders the stone through a vtkOpalSpectralRender
 * for the active camera and the viewport's size, and draws the image as a
 * quad over the viewport that writes the stone's depth: other props in front
 * of the stone hide it and props behind it are hidden, and pixels that miss
 * the stone are left as they are (docs/design.md §5.2). While the window
 * renders interactively (its desired update rate above 1 frame per second:
 * ParaView's InteractiveRender, used during a drag, sets 5) the frame is a preview
 * (Quality preview, a quarter of the pixels); a still render uses
 * StillQuality. With DeferFinalFrames on (the GUI's still renders), a final
 * still frame is not waited for: the render draws the preview and the final
 * frame is rendered on a worker thread, drawn by a later render once it has
 * finished (GetReadyFinalFrame says when; docs/design.md §5.2). With
 * Headlight on the light sits at the eye, the paper's set-up (previews keep
 * the last still frame's light, so a drag needs no light pass); off, the
 * render filter's LightPosition is used. The camera's view angle is taken as
 * it is; a parallel projection is rendered in perspective.
 */
#pragma once

#include "vtkImageData.h" // for vtkNew<vtkImageData>
#include "vtkNew.h"
#include "vtkOpalRepresentationModule.h" // for export macro
#include "vtkProp.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <vector>

class vtkCamera;
class vtkOpalSpectralRender;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
namespace opal
{
class FrameBudget;
struct RenderParameters;
}

class VTKOPALREPRESENTATION_EXPORT vtkOpalSpectralImageActor : public vtkProp
{
public:
  static vtkOpalSpectralImageActor* New();
  vtkTypeMacro(vtkOpalSpectralImageActor, vtkProp);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The render filter (its input: the opal volume) that makes each frame.
  void SetRender(vtkOpalSpectralRender* render);

  ///@{
  /// The light at the eye (default) or at the render filter's LightPosition.
  vtkSetMacro(Headlight, bool);
  vtkGetMacro(Headlight, bool);
  ///@}

  ///@{
  /// Quality of still frames: 0 final (default), 1 preview.
  vtkSetClampMacro(StillQuality, int, 0, 1);
  vtkGetMacro(StillQuality, int);
  ///@}

  ///@{
  /// Seconds an interactive frame should take (default 0.1): each preview's
  /// PreviewScale is chosen from the measured cost of the last ones. 0: the
  /// render filter's PreviewScale as it is.
  void SetFrameBudget(double seconds);
  double GetFrameBudget() const;
  ///@}

  /// PreviewScale of the last preview drawn (0 before any).
  vtkGetMacro(LastPreviewScale, int);

  ///@{
  /// Still final frames on a worker thread, drawn by a later render (the
  /// preview meanwhile); off (default): a still render waits for its frame.
  vtkSetMacro(DeferFinalFrames, bool);
  vtkGetMacro(DeferFinalFrames, bool);
  ///@}

  /// A final frame finished on the worker and not yet drawn: its id (> 0),
  /// the same until it is drawn or dropped; 0 if none. The view should render.
  vtkMTimeType GetReadyFinalFrame();

  /// The refinement under way: its pass (1-based) and their number, and the
  /// pass's fraction done; false if none runs (the view shows its last pass).
  bool GetRefinementProgress(int& pass, int& passes, double& fraction);

  /// Stops a final frame rendering on the worker (the stone is hidden or leaves the view).
  void CancelFinalFrame();

  /// The stone's bounds, for the camera's reset and clipping range.
  void SetStoneBounds(const double bounds[6]);
  double* GetBounds() override;

  /// Quality (0 final, 1 preview) of the last frame drawn; -1 before any.
  vtkGetMacro(LastQuality, int);

  int RenderOpaqueGeometry(vtkViewport* viewport) override;
  vtkTypeBool HasTranslucentPolygonalGeometry() override { return 0; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkOpalSpectralImageActor();
  ~vtkOpalSpectralImageActor() override;

private:
  vtkOpalSpectralImageActor(const vtkOpalSpectralImageActor&) = delete;
  void operator=(const vtkOpalSpectralImageActor&) = delete;

  // Points the render filter at the camera and size; the image to draw, or null.
  vtkImageData* UpdateFrame(vtkRenderer* renderer, bool interactive);
  // The camera and the image size into the render filter; false if there is nothing to draw.
  bool AimRender(vtkRenderer* renderer);
  // A still final frame not waited for: the preview now, then the refinement
  // passes, each drawn once finished, the last the final frame.
  vtkImageData* DeferredFrame(const double eye[3]);
  // True, said once, while the eye is inside the stone (nothing to draw).
  bool EyeInsideStone(const double eye[3]);
  // The passes of this key started on the worker, the preview first if asked.
  void StartRefinement(vtkMTimeType key, const double eye[3], bool withPreview);
  // A finished refinement pass taken into FinalFrame, and the next one started.
  void TakeRefinement(const double eye[3]);
  // The preview's PreviewScale from the frame budget (interactive frames).
  void ChoosePreviewScale();
  // The render filter's output brought up to date; null if it has no image.
  vtkImageData* UpdatedOutput();
  // The image and each pixel's distance along its ray, as textures.
  void UploadFrame(vtkOpenGLRenderWindow* window, vtkImageData* image);
  // The quad, its depth from the camera's current projection.
  void DrawFrame(vtkOpenGLRenderWindow* window, vtkCamera* camera, double aspect);

  vtkSmartPointer<vtkOpalSpectralRender> Render;
  bool Headlight = true;
  int StillQuality = 0;
  int LastQuality = -1;
  double StoneBounds[6] = { 0, -1, 0, -1, 0, -1 };
  vtkNew<vtkTextureObject> ColourTexture;
  vtkNew<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  bool DeferFinalFrames = false;
  vtkNew<vtkImageData> FinalFrame; // the last final frame taken from the worker
  std::unique_ptr<opal::FrameBudget> Budget;
  int LastPreviewScale = 0;
  int ViewPixels[2] = { 0, 0 }; // the frame's size in the view's pixels
  // The passes of the held view (opal::refinementPasses), the one started, and the one FinalFrame holds.
  std::vector<opal::RenderParameters> Passes;
  std::size_t StartedPass = 0;
  std::size_t DrawnPass = 0;
  // Ids of deferred final frames: the render filter's MTime with the preview's
  // settings (the same until the camera, the size, a setting or the volume changes).
  vtkMTimeType StartedKey = 0; // of the frame last started on the worker
  vtkMTimeType FinalKey = 0;   // of the frame FinalFrame holds
  // The render filter's MTime at an update that failed (and said why): not
  // asked again, at every frame, until it changes (the executive would add
  // its own error each time).
  vtkMTimeType FailedKey = 0;
  vtkImageData* UploadedImage = nullptr; // the image the textures hold (identity only)
  vtkMTimeType UploadedTime = 0;         // and its MTime then
  bool WarnedParallel = false;
  bool SaidEyeInside = false;
  double TanHalfViewAngle = 0; // of the frame's vertical view angle
  double FrameAspect = 1;      // width / height of the frame's image
};
