// The kinds of opal (docs/design.md §2.11) look like their stones: rendered
// with the same light and eye, black opal's body is dark (below a quarter of
// white opal's luminance), fire opal's body is orange to yellow, and crystal
// opal's body is more transparent than white opal's; every kind is finite
// with the validation layer silent. The body is rendered without its domains;
// its luminance is the median pixel's (the highlight aside), its hue the mean
// colour's (single pixels vary with the random scattering field).
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalPresets.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
struct Body
{
  double Luminance;     // median Y of the stone's pixels
  double Hue;           // degrees, of the stone's mean linear sRGB
  double Transmittance; // exp(-mean extinction at 550 nm x the stone's height)
};

double hueOf(double r, double g, double b)
{
  const double hi = std::max({ r, g, b }), lo = std::min({ r, g, b });
  if (hi - lo <= 0)
  {
    return -1; // grey
  }
  const double h = hi == r ? 60.0 * std::fmod((g - b) / (hi - lo) + 6.0, 6.0)
    : hi == g              ? 60.0 * ((b - r) / (hi - lo) + 2.0)
                           : 60.0 * ((r - g) / (hi - lo) + 4.0);
  return h;
}

Body renderBody(opaltest::SceneRenderer& renderer, const std::string& name)
{
  opal::ModelParameters model;
  OPAL_CHECK(model.applyPreset(opal::presetIndexByName(name)), name + " is a preset");
  model.Dimensions = { 40, 20, 50 };
  model.DomainCount = 0; // the body alone: at this grid the domains would cover much of the stone
  const auto volume = opal::buildVolume(model);
  opal::RenderParameters view;
  view.ImageSize = { 48, 64 };
  view.Exposure = 1.0; // equal exposure for every kind
  const opal::RenderImage image = renderer.render(volume->renderVolume(), view);
  OPAL_CHECK(opal::nonFiniteArray(image).empty(), name + ": every value of the image is finite");
  std::vector<std::size_t> stone;
  for (std::size_t i = 0; i < image.Depth.size(); ++i)
  {
    if (image.Depth[i] > 0) stone.push_back(i);
  }
  std::sort(stone.begin(), stone.end(),
    [&image](std::size_t a, std::size_t b) { return image.XYZ[3 * a + 1] < image.XYZ[3 * b + 1]; });
  const std::size_t median = stone.at(stone.size() / 2);
  double rgb[3] = { 0, 0, 0 };
  for (const std::size_t i : stone)
  {
    for (int c = 0; c < 3; ++c) rgb[c] += image.Radiance[3 * i + c] / static_cast<double>(stone.size());
  }
  const opal::RenderVolume& v = volume->renderVolume();
  double extinction = 0;
  long long inside = 0;
  for (std::size_t i = 0; i < v.voxelCount(); ++i)
  {
    if (v.SurfaceDistance[i] <= 0)
    {
      extinction += v.ScatteringCoefficient[i] + (v.AbsorptionCoefficient ? v.AbsorptionCoefficient[i] : 0.0f);
      ++inside;
    }
  }
  OPAL_CHECK(renderer.context().validationMessages().empty(), name + ": the validation layer is silent");
  std::printf("%s body: median Y %.4g, mean linear sRGB %.4g %.4g %.4g\n", name.c_str(), image.XYZ[3 * median + 1], rgb[0],
    rgb[1], rgb[2]);
  return { image.XYZ[3 * median + 1], hueOf(rgb[0], rgb[1], rgb[2]),
    std::exp(-extinction / static_cast<double>(inside) * model.PhysicalSize[1]) };
}
} // namespace

int TestOpalOpalTypes(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  const Body white = renderBody(*renderer, "white-opal");
  const Body black = renderBody(*renderer, "black-opal");
  const Body crystal = renderBody(*renderer, "crystal-opal");
  const Body fire = renderBody(*renderer, "fire-opal");
  renderBody(*renderer, "boulder-opal");
  OPAL_CHECK(black.Luminance < 0.25 * white.Luminance,
    "black opal's body is dark: Y " + std::to_string(black.Luminance) + " vs white " + std::to_string(white.Luminance));
  // Orange (about 20-40 degrees) to yellow (60 degrees).
  OPAL_CHECK(fire.Hue >= 15 && fire.Hue <= 60, "fire opal's body is orange to yellow: hue " + std::to_string(fire.Hue));
  OPAL_CHECK(crystal.Transmittance > white.Transmittance + 0.2,
    "crystal opal is more transparent than white: " + std::to_string(crystal.Transmittance) + " vs " +
      std::to_string(white.Transmittance));
  return opaltest::finish("TestOpalOpalTypes");
}
