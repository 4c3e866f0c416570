// Every kind of opal renders from every side, as the live "Opal Spectral"
// representation frames it: no preset placement (the preset's Bragg model and
// planes set as ParaView sets them), the light at the eye (the headlight), the
// eye along +-x, +-y, +-z and obliquely, final and preview quality. Each frame
// must complete with every output array finite (the session refuses an image
// holding a NaN: the stone would vanish from the view) and show the stone: a
// tenth of the pixels hit it and most of those are lit.
//
// Black opal from the side once failed in the preview with a NaN in Radiance:
// a view ray running lengthwise through its backing (5 /mm, grey) crosses a
// domain deep inside it, and the energy-conserving round behind that crossing
// gathers only samples ~86 grey optical depths from light and eye. Their node
// sums start at the float's smallest values, the shorter wavelengths' nodes
// underflow to 0 while the longest's stays positive, and log 0 in the spectral
// resampling made NaN (docs/design.md §3.4). Fire opal (its body absorbs the
// short wavelengths' nodes away first) and boulder opal (its ironstone) failed
// alike from the sides: before the nodes' logs were guarded this test failed
// 19 frames (black opal's previews from +x, +z and -z; fire and boulder opal
// from +-x and +-z, final and preview), and with only that guard none.
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include <array>
#include <exception>
#include <optional>
#include <string>

namespace
{
struct Side
{
  const char* Name;
  std::array<double, 3> Direction; // from the stone's centre towards the eye
  std::array<double, 3> Up;
};

// Along the long axis z the image's up is +y; looking along y it is -z, the
// paper's orientation.
const std::array<Side, 7> Sides{ { { "+x", { 1, 0, 0 }, { 0, 1, 0 } }, { "-x", { -1, 0, 0 }, { 0, 1, 0 } },
  { "+y", { 0, 1, 0 }, { 0, 0, -1 } }, { "-y", { 0, -1, 0 }, { 0, 0, -1 } }, { "+z", { 0, 0, 1 }, { 0, 1, 0 } },
  { "-z", { 0, 0, -1 }, { 0, 1, 0 } }, { "oblique", { 0.6, 0.6, 0.53 }, { 0, 1, 0 } } } };

// The frame, or nothing if it failed (a check says why).
std::optional<opal::RenderImage> renderChecked(
  opaltest::SceneRenderer& renderer, const opal::ResolvedFrame& frame, const std::string& what)
{
  try
  {
    opal::RenderFrame rendered = renderer.Session.render(frame);
    OPAL_CHECK(rendered.Status == opal::FrameStatus::Completed, what + ": the frame completes");
    OPAL_CHECK(opal::nonFiniteArray(rendered.Image).empty() && opaltest::allFinite(rendered.Image),
      what + ": every value of the image is finite");
    return std::move(rendered.Image);
  }
  catch (const std::exception& e)
  {
    OPAL_CHECK(false, what + ": " + e.what());
    return std::nullopt;
  }
}

// The camera the representation sets: eye and headlight 40 mm from the box's
// centre, ParaView's 30 degrees. The preview is asked at 100 x 76 (it renders
// 50 x 38): black opal's failing pixels are a few among its previews' pixels.
opal::RenderParameters sideView(const Side& side, const std::array<double, 3>& centre, opal::RenderQuality quality)
{
  opal::RenderParameters view;
  view.ScatteringOrders = opal::ScatteringOrdersKind::Volume; // the volume's, as ParaView's default
  view.ScatteringPhotons = 1 << 11; // the every-order field's noise is not what is tested: 8x cheaper
  view.Quality = quality;
  const bool preview = quality == opal::RenderQuality::Preview;
  view.ImageSize = preview ? std::array<int, 2>{ 100, 76 } : std::array<int, 2>{ 32, 24 };
  view.FocalPoint = centre;
  for (int a = 0; a < 3; ++a)
  {
    view.EyePosition[a] = centre[a] + 40.0 * side.Direction[a];
  }
  view.LightPosition = view.EyePosition;
  view.ViewUp = side.Up;
  view.ViewAngle = 30;
  return view;
}

// A tenth of the image is the stone (the frame at 40 mm shows it whole from
// every side), and nine in ten of its pixels are lit: the headlight reaches
// whatever the eye sees.
void checkStoneShown(const opal::RenderImage& image, const std::string& what)
{
  std::size_t hit = 0, lit = 0;
  for (std::size_t i = 0; i < image.Depth.size(); ++i)
  {
    const float radiance = image.Radiance[3 * i] + image.Radiance[3 * i + 1] + image.Radiance[3 * i + 2];
    hit += image.Depth[i] > 0 ? 1 : 0;
    lit += image.Depth[i] > 0 && radiance > 0 ? 1 : 0;
  }
  OPAL_CHECK(hit * 10 >= image.Depth.size(),
    what + ": the stone is seen (" + std::to_string(hit) + " of " + std::to_string(image.Depth.size()) + " pixels)");
  OPAL_CHECK(lit * 10 >= hit * 9,
    what + ": the stone is lit (" + std::to_string(lit) + " of its " + std::to_string(hit) + " pixels)");
}

void renderKind(opaltest::SceneRenderer& renderer, const std::string& preset)
{
  opal::ModelParameters model;
  OPAL_CHECK(model.applyPreset(opal::presetIndexByName(preset)), preset + " is a preset");
  model.Dimensions = { 32, 16, 40 };
  const auto volume = opal::buildVolume(model);
  renderer.Session.setVolume(volume->renderVolume());
  const opal::VolumeRenderHints hints = opal::renderHints(opal::presetIndexByName(preset), model.RefractiveIndex);
  const std::array<double, 3> centre{ 0, model.PhysicalSize[1] / 2, 0 };
  for (const Side& side : Sides)
  {
    for (const auto quality : { opal::RenderQuality::Final, opal::RenderQuality::Preview })
    {
      opal::RenderParameters view = sideView(side, centre, quality);
      view.BraggModel = hints.BraggModel.value_or(view.BraggModel);
      view.LatticePlanes = hints.LatticePlanes.value_or(view.LatticePlanes);
      const std::string what =
        preset + " from " + side.Name + (quality == opal::RenderQuality::Final ? " final" : " preview");
      // The representation's frame: no preset placement.
      const std::optional<opal::RenderImage> image =
        renderChecked(renderer, opal::resolveFrame(view, hints, false), what);
      if (image)
      {
        checkStoneShown(*image, what);
      }
    }
  }
}
} // namespace

int TestOpalEverySide(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  for (const char* preset : { "white-opal", "black-opal", "crystal-opal", "fire-opal", "boulder-opal" })
  {
    renderKind(*renderer, preset);
  }
  OPAL_CHECK(renderer->context().validationMessages().empty(), "the validation layer is silent");
  return opaltest::finish("TestOpalEverySide");
}
