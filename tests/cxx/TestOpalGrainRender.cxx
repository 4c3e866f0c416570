// A render of each domain layout (docs/design.md §2.9): the paper's polygons
// and Voronoi grains (the harlequin and pinfire presets) each give a finite
// image in which domains diffract, with the validation layer silent.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalPresets.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
// Share of the stone's pixels with a diffracting domain.
double diffractingShare(const opal::RenderImage& image)
{
  long long hit = 0, diffracting = 0;
  for (std::size_t i = 0; i < image.Depth.size(); ++i)
  {
    hit += image.Depth[i] > 0 ? 1 : 0;
    diffracting += image.Depth[i] > 0 && image.DominantBraggWavelength[i] > 0 ? 1 : 0;
  }
  return hit > 0 ? static_cast<double>(diffracting) / hit : 0.0;
}

void checkLayout(opaltest::SceneRenderer& renderer, const std::string& name, opal::ModelParameters model)
{
  model.Dimensions = { 48, 24, 60 };
  const auto volume = opal::buildVolume(model);
  opal::RenderParameters view;
  view.ImageSize = { 64, 48 };
  const opal::RenderImage image = renderer.render(volume->renderVolume(), view);
  OPAL_CHECK(opal::nonFiniteArray(image).empty(), name + ": every value of the image is finite");
  const double share = diffractingShare(image);
  OPAL_CHECK(share > 0.05, name + ": domains diffract in " + std::to_string(100 * share) + "% of the stone's pixels");
  const auto messages = renderer.context().validationMessages();
  OPAL_CHECK(messages.empty(), name + ": the validation layer is silent");
}
} // namespace

int TestOpalGrainRender(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  opal::ModelParameters polygons;
  polygons.DomainCount = 40;
  checkLayout(*renderer, "polygons", polygons);
  for (const char* preset : { "harlequin", "pinfire" })
  {
    opal::ModelParameters grains;
    grains.applyPreset(opal::presetIndexByName(preset));
    checkLayout(*renderer, preset, grains);
  }
  return opaltest::finish("TestOpalGrainRender");
}
