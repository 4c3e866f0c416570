#include "vtkOpalSpectralImageActor.h"

#include "OpalFrameBudget.h"
#include "OpalRefinementPasses.h"
#include "OpalRenderParameters.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpalSpectralRender.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace
{
// The frame as a quad over the viewport: the stone's colour where it was hit,
// and the depth of that point under the camera's current projection (the
// clipping range changes with the other props, the distances do not);
// misses are discarded, so the scene behind shows.
const char* const FrameFragmentShader = R"(//VTK::System::Dec
in vec2 texCoord;
uniform sampler2D colourTexture;
uniform sampler2D distanceTexture;
// The ray through a point of the frame, in the camera's frame: (ndc * rayScale, -1).
uniform vec2 rayScale;
// The part of the frame this viewport shows: origin and size, in frame units
// (0 1 1 1 untiled; a tile of a screenshot larger than the window otherwise).
uniform vec4 tileOfFrame;
// The projection's z and w rows, applied to (z_view, 1).
uniform vec4 projectionZW;
//VTK::Output::Dec
void main()
{
  vec2 frameCoord = tileOfFrame.xy + texCoord * tileOfFrame.zw;
  float distance = texture(distanceTexture, frameCoord).r;
  if (!(distance > 0.0))
  {
    discard;
  }
  vec2 ndc = 2.0 * frameCoord - 1.0;
  float zView = -distance / length(vec3(ndc * rayScale, 1.0));
  float zClip = projectionZW.x * zView + projectionZW.y;
  float wClip = projectionZW.z * zView + projectionZW.w;
  gl_FragData[0] = vec4(texture(colourTexture, frameCoord).rgb, 1.0);
  gl_FragDepth = clamp(0.5 * zClip / wClip + 0.5, 0.0, 1.0);
}
)";

// RGB to RGBA: rows of four bytes need no unpack alignment.
std::vector<unsigned char> rgbaOf(vtkDataArray* rgb, vtkIdType pixels)
{
  std::vector<unsigned char> rgba(static_cast<std::size_t>(4 * pixels), 255);
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[static_cast<std::size_t>(4 * p + c)] = static_cast<unsigned char>(rgb->GetComponent(p, c));
    }
  }
  return rgba;
}
bool insideBox(const double* point, const double bounds[6])
{
  return point[0] >= bounds[0] && point[0] <= bounds[1] && point[1] >= bounds[2] && point[1] <= bounds[3] &&
    point[2] >= bounds[4] && point[2] <= bounds[5];
}

// The up direction the camera's view transform actually uses (VTK keeps a
// ViewUp parallel to the view direction and patches it there); false if degenerate.
bool viewUpOf(vtkCamera* camera, double up[3])
{
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  for (int a = 0; a < 3; ++a)
  {
    up[a] = view->GetElement(1, a);
  }
  const double length = vtkMath::Norm(up);
  return std::isfinite(length) && length > 0.5;
}
} // namespace

vtkStandardNewMacro(vtkOpalSpectralImageActor);

vtkOpalSpectralImageActor::vtkOpalSpectralImageActor()
  : Budget(std::make_unique<opal::FrameBudget>())
{
}

vtkOpalSpectralImageActor::~vtkOpalSpectralImageActor() = default;

void vtkOpalSpectralImageActor::SetRender(vtkOpalSpectralRender* render)
{
  this->Render = render;
  this->Modified();
}

void vtkOpalSpectralImageActor::SetStoneBounds(const double bounds[6])
{
  std::copy(bounds, bounds + 6, this->StoneBounds);
  this->Modified();
}

double* vtkOpalSpectralImageActor::GetBounds()
{
  return this->StoneBounds[0] <= this->StoneBounds[1] ? this->StoneBounds : nullptr;
}

int vtkOpalSpectralImageActor::RenderOpaqueGeometry(vtkViewport* viewport)
{
  auto* renderer = vtkRenderer::SafeDownCast(viewport);
  auto* window = renderer ? vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow()) : nullptr;
  // Not in a selection (picking) pass: the stone has no cells to pick.
  if (!window || !this->Render || renderer->GetSelector())
  {
    return 0;
  }
  const bool interactive = window->GetDesiredUpdateRate() > 1.0;
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* image = this->UpdateFrame(renderer, interactive);
  if (!image)
  {
    return 0;
  }
  const bool fresh = image != this->UploadedImage || image->GetMTime() != this->UploadedTime;
  if (fresh)
  {
    this->UploadFrame(window, image);
  }
  // The budget learns from previews rendered here, their upload included.
  if (interactive && fresh && this->LastQuality == 1)
  {
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    this->Budget->record(static_cast<double>(image->GetNumberOfPoints()), seconds.count());
  }
  this->DrawFrame(window, renderer->GetActiveCamera(), renderer->GetTiledAspectRatio());
  return 1;
}

// An eye in the stone's box but outside the stone renders (the render
// leaves the opal's surface to the rays); inside the stone nothing is drawn
// and it is said once, until the eye leaves it. Before the first frame the
// whole box is left out, silently: ParaView's default camera sits in it until
// the view first frames the stone.
bool vtkOpalSpectralImageActor::EyeInsideStone(const double eye[3])
{
  if (!insideBox(eye, this->StoneBounds))
  {
    this->SaidEyeInside = false;
    return false;
  }
  if (this->LastQuality < 0)
  {
    return true;
  }
  if (!this->Render->MostOverSharingRanks(this->Render->IsEyeInsideOpal() ? 1 : 0))
  {
    this->SaidEyeInside = false;
    return false;
  }
  if (!this->SaidEyeInside)
  {
    vtkWarningMacro("The eye is inside the opal: Opal Spectral draws nothing until the camera leaves the stone.");
    this->SaidEyeInside = true;
  }
  return true;
}

void vtkOpalSpectralImageActor::SetFrameBudget(double seconds)
{
  this->Budget->setBudget(seconds, opal::RenderParameters{}.PreviewScale);
  this->Modified();
}

double vtkOpalSpectralImageActor::GetFrameBudget() const
{
  return this->Budget->budget();
}

void vtkOpalSpectralImageActor::ChoosePreviewScale()
{
  this->Render->SetPreviewScale(
    this->Render->MostOverSharingRanks(this->Budget->scaleFor(this->ViewPixels[0], this->ViewPixels[1])));
  this->LastPreviewScale = this->Render->GetPreviewScale();
}

vtkImageData* vtkOpalSpectralImageActor::UpdateFrame(vtkRenderer* renderer, bool interactive)
{
  if (!this->AimRender(renderer))
  {
    return nullptr;
  }
  const double* eye = renderer->GetActiveCamera()->GetPosition();
  if (this->EyeInsideStone(eye))
  {
    return nullptr;
  }
  if (!interactive && this->StillQuality == 0 && this->DeferFinalFrames)
  {
    return this->DeferredFrame(eye);
  }
  // A drag before the first view has arrived draws nothing rather than wait
  // for what the worker is making (the device's volume, the pipelines, the
  // light field); the still render at its end starts the first view again.
  if (interactive && this->DeferFinalFrames && this->LastQuality < 0)
  {
    return nullptr;
  }
  // The headlight follows the eye at still frames; a preview keeps the last
  // still frame's light, so dragging re-marches without rerunning the light
  // pass (the light field depends on the light, not on the eye).
  if (this->Headlight && (!interactive || this->LastQuality < 0))
  {
    this->Render->SetLightPosition(eye);
  }
  this->LastQuality = interactive ? 1 : this->StillQuality;
  this->Render->SetQuality(this->LastQuality);
  if (interactive)
  {
    this->ChoosePreviewScale();
  }
  return this->UpdatedOutput();
}

bool vtkOpalSpectralImageActor::AimRender(vtkRenderer* renderer)
{
  int width = 0, height = 0;
  renderer->GetTiledSize(&width, &height);
  // A screenshot larger than the window is drawn in tiles: the frame is the
  // whole image (rendered once), each tile draws its part (DrawFrame).
  int tileScale[2] = { 1, 1 };
  renderer->GetRenderWindow()->GetTileScale(tileScale);
  width *= tileScale[0];
  height *= tileScale[1];
  vtkCamera* camera = renderer->GetActiveCamera();
  double up[3];
  if (width < 1 || height < 1 || this->Render->GetNumberOfInputConnections(0) < 1 || !viewUpOf(camera, up))
  {
    return false;
  }
  if (camera->GetParallelProjection() && !this->WarnedParallel)
  {
    vtkWarningMacro("Opal Spectral renders in perspective; the view's parallel projection is not used.");
    this->WarnedParallel = true;
  }
  this->Render->SetImageSize(width, height);
  this->ViewPixels[0] = width;
  this->ViewPixels[1] = height;
  this->Render->SetEyePosition(camera->GetPosition());
  this->Render->SetFocalPoint(camera->GetFocalPoint());
  this->Render->SetViewUp(up);
  // A tile's camera sees 1/scale of the image's angle, centred on the tile
  // by its WindowCenter (ParaView's tiled screenshots): the whole frame's
  // angle is scale times wider in tangent.
  const bool horizontal = camera->GetUseHorizontalViewAngle();
  double tangent = std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2) * tileScale[horizontal ? 0 : 1];
  if (horizontal)
  {
    tangent *= static_cast<double>(height) / width;
  }
  const double angle = vtkMath::DegreesFromRadians(2 * std::atan(tangent));
  this->Render->SetViewAngle(angle);
  this->TanHalfViewAngle = std::tan(vtkMath::RadiansFromDegrees(angle) / 2);
  return true;
}

// docs/design.md §5.2: the render filter keeps the preview's settings (as
// while dragging), so their MTime names this camera, size, settings and
// volume; the refinement passes of them render on the worker once, one after
// another, and the first render after each finished draws it.
vtkImageData* vtkOpalSpectralImageActor::DeferredFrame(const double eye[3])
{
  if (this->Headlight && this->LastQuality < 0)
  {
    this->Render->SetLightPosition(eye);
  }
  this->Render->SetQuality(1);
  if (this->Render->GetMTime() == this->StartedKey)
  {
    this->TakeRefinement(eye);
  }
  const vtkMTimeType key = this->Render->GetMTime();
  if (key == this->FinalKey)
  {
    this->LastQuality = this->DrawnPass + 1 == this->Passes.size() ? 0 : 1;
    return this->FinalFrame;
  }
  // The first view renders even its preview on the worker: the device's
  // volume, the pipelines and the first light field would hold the GUI for
  // seconds. Otherwise the preview is re-rendered only if the settings
  // changed, which cancels a pass of the old ones.
  const bool firstView = this->LastQuality < 0;
  vtkImageData* preview = firstView ? nullptr : this->UpdatedOutput();
  if (!preview && !firstView)
  {
    return nullptr;
  }
  if (key != this->StartedKey)
  {
    this->StartRefinement(key, eye, firstView);
  }
  if (preview)
  {
    this->LastQuality = 1;
  }
  return preview;
}

void vtkOpalSpectralImageActor::StartRefinement(vtkMTimeType key, const double eye[3], bool withPreview)
{
  const opal::RenderParameters preview = this->Render->GetRenderParameters();
  opal::RenderParameters finalFrame = preview;
  finalFrame.Quality = opal::RenderQuality::Final;
  if (this->Headlight)
  {
    std::copy(eye, eye + 3, finalFrame.LightPosition.begin());
  }
  this->Passes = opal::refinementPasses(preview, finalFrame);
  if (withPreview)
  {
    this->Passes.insert(this->Passes.begin(), preview);
  }
  // Once per key: a pass that failed (said in an error) is not retried until something changes.
  this->StartedKey = key;
  this->StartedPass = 0;
  this->Render->StartBackgroundFrame(this->Passes.front());
}

void vtkOpalSpectralImageActor::TakeRefinement(const double eye[3])
{
  if (this->Render->GetBackgroundFrameState() != 2 || !this->Render->TakeBackgroundFrame(this->FinalFrame))
  {
    return;
  }
  this->DrawnPass = this->StartedPass;
  this->FinalKey = this->StartedKey;
  if (this->StartedPass + 1 < this->Passes.size())
  {
    this->Render->StartBackgroundFrame(this->Passes[++this->StartedPass]);
    return;
  }
  // Previews from here on keep this still frame's light, as after a waited-for one.
  if (this->Headlight)
  {
    this->Render->SetLightPosition(eye);
  }
  this->FinalKey = this->StartedKey = this->Render->GetMTime();
}

vtkImageData* vtkOpalSpectralImageActor::UpdatedOutput()
{
  const vtkMTimeType key = this->Render->GetMTime();
  if (key == this->FailedKey)
  {
    return nullptr;
  }
  if (!this->Render->GetExecutive()->Update())
  {
    this->FailedKey = key;
    return nullptr;
  }
  vtkImageData* image = this->Render->GetOutput();
  const bool drawable = image->GetNumberOfPoints() > 0 && image->GetPointData()->GetArray("RGB") &&
    vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Depth"));
  return drawable ? image : nullptr;
}

vtkMTimeType vtkOpalSpectralImageActor::GetReadyFinalFrame()
{
  const bool ready = this->Render && this->GetVisibility() && this->StartedKey == this->Render->GetMTime() &&
    this->Render->GetBackgroundFrameState() == 2;
  // Each pass its own id: the GUI renders the view once for each.
  return ready ? this->StartedKey * 4 + this->StartedPass : 0;
}

bool vtkOpalSpectralImageActor::GetRefinementProgress(int& pass, int& passes, double& fraction)
{
  if (!this->Render || this->StartedKey != this->Render->GetMTime() || this->Render->GetBackgroundFrameState() != 1)
  {
    return false;
  }
  pass = static_cast<int>(this->StartedPass) + 1;
  passes = static_cast<int>(this->Passes.size());
  fraction = this->Render->GetBackgroundFrameProgress();
  return true;
}

void vtkOpalSpectralImageActor::CancelFinalFrame()
{
  if (this->Render)
  {
    this->Render->CancelBackgroundFrame();
  }
  this->StartedKey = 0; // started again at the next still render
}

void vtkOpalSpectralImageActor::UploadFrame(vtkOpenGLRenderWindow* window, vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  const vtkIdType pixels = static_cast<vtkIdType>(dims[0]) * dims[1];
  std::vector<unsigned char> rgba = rgbaOf(image->GetPointData()->GetArray("RGB"), pixels);
  // The render writes Depth as contiguous floats: uploaded as it is.
  auto* depth = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Depth"));
  this->ColourTexture->SetContext(window);
  this->ColourTexture->Create2DFromRaw(dims[0], dims[1], 4, VTK_UNSIGNED_CHAR, rgba.data());
  // A preview has half the pixels each way: smooth it as it is stretched.
  this->ColourTexture->SetMinificationFilter(vtkTextureObject::Linear);
  this->ColourTexture->SetMagnificationFilter(vtkTextureObject::Linear);
  this->DepthTexture->SetContext(window);
  this->DepthTexture->Create2DFromRaw(dims[0], dims[1], 1, VTK_FLOAT, depth->GetPointer(0));
  this->DepthTexture->SetMinificationFilter(vtkTextureObject::Nearest);
  this->DepthTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->FrameAspect = static_cast<double>(dims[0]) / dims[1];
  this->UploadedImage = image;
  this->UploadedTime = image->GetMTime();
}

void vtkOpalSpectralImageActor::DrawFrame(vtkOpenGLRenderWindow* window, vtkCamera* camera, double aspect)
{
  if (!this->Quad)
  {
    this->Quad = std::make_unique<vtkOpenGLQuadHelper>(window, nullptr, FrameFragmentShader, "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  vtkShaderProgram* program = this->Quad->Program;
  if (!program || !program->GetCompiled())
  {
    vtkErrorMacro("The Opal Spectral frame shader did not compile.");
    return;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglDepthFunc(GL_LEQUAL);
  this->ColourTexture->Activate();
  this->DepthTexture->Activate();
  program->SetUniformi("colourTexture", this->ColourTexture->GetTextureUnit());
  program->SetUniformi("distanceTexture", this->DepthTexture->GetTextureUnit());
  const float rayScale[2] = { static_cast<float>(this->TanHalfViewAngle * this->FrameAspect),
    static_cast<float>(this->TanHalfViewAngle) };
  program->SetUniform2f("rayScale", rayScale);
  double tile[4];
  window->GetTileViewport(tile);
  const float tileOfFrame[4] = { static_cast<float>(tile[0]), static_cast<float>(tile[1]),
    static_cast<float>(tile[2] - tile[0]), static_cast<float>(tile[3] - tile[1]) };
  program->SetUniform4f("tileOfFrame", tileOfFrame);
  vtkMatrix4x4* projection = camera->GetProjectionTransformMatrix(aspect, -1, 1);
  const float projectionZW[4] = { static_cast<float>(projection->GetElement(2, 2)),
    static_cast<float>(projection->GetElement(2, 3)), static_cast<float>(projection->GetElement(3, 2)),
    static_cast<float>(projection->GetElement(3, 3)) };
  program->SetUniform4f("projectionZW", projectionZW);
  this->Quad->Render();
  this->DepthTexture->Deactivate();
  this->ColourTexture->Deactivate();
}

void vtkOpalSpectralImageActor::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.reset();
  this->ColourTexture->ReleaseGraphicsResources(window);
  this->DepthTexture->ReleaseGraphicsResources(window);
  // Nothing left to release against a context that may be gone by the destructor.
  this->ColourTexture->SetContext(nullptr);
  this->DepthTexture->SetContext(nullptr);
  this->UploadedImage = nullptr;
  this->UploadedTime = 0;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkOpalSpectralImageActor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Headlight: " << this->Headlight << "\n";
  os << indent << "StillQuality: " << this->StillQuality << "\n";
  os << indent << "DeferFinalFrames: " << this->DeferFinalFrames << "\n";
  os << indent << "LastQuality: " << this->LastQuality << "\n";
}
