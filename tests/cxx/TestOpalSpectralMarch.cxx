// The view march's two shortcuts (docs/design.md §3.4) against what they
// replace: the body's scattering accumulated on 16 spectral nodes and
// resampled equals the per-wavelength evaluation (fig12: within 0.01% mean and
// 0.1% at worst, of the XYZ over the image, for the default wavelength table
// and for 400-700 nm by 5 nm); domain crossings recorded and
// diffracted after the walk, in rounds when a ray crosses more domains than
// the record holds (8), equal the sum of the domains rendered one at a time.
// A thick body, where a node's sum underflows, renders finite and as close;
// so does a body that absorbs red, whose longest wavelength's node dies first
// (with energy conservation's rounds too).
// The preview quality renders half the size and about the same image.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

namespace
{
// Relative differences of b from a: the L1 ratio over the image, and the
// worst pixel value relative to itself (or to a thousandth of the brightest,
// for the dark ones).
struct RelativeDifference
{
  double Mean = 0;
  double Max = 0;
};

RelativeDifference relativeDifference(const opal::RenderImage& a, const opal::RenderImage& b)
{
  RelativeDifference d;
  double sum = 0, total = 0, brightest = 0;
  for (float value : a.XYZ)
  {
    brightest = std::max(brightest, std::fabs(static_cast<double>(value)));
  }
  for (std::size_t i = 0; i < a.XYZ.size(); ++i)
  {
    const double scale = std::max(std::fabs(static_cast<double>(a.XYZ[i])), 1e-3 * brightest);
    d.Max = std::max(d.Max, std::fabs(a.XYZ[i] - b.XYZ[i]) / scale);
    sum += std::fabs(a.XYZ[i] - b.XYZ[i]);
    total += std::fabs(a.XYZ[i]);
  }
  d.Mean = total > 0 ? sum / total : 0;
  return d;
}

// Nodes against every wavelength for a wavelength table: the march's
// pipeline is specialised on the table's first centre and step (its
// resampling folds each bin's nodes and weights), so a second table checks
// that they reach it.
void checkSpectralNodes(opaltest::SceneRenderer& renderer, const opal::RenderVolume& volume,
  std::array<double, 2> range, double step, const RelativeDifference& allowed = { 1e-4, 1e-3 },
  bool energyConservation = false)
{
  opal::RenderParameters p;
  p.EnergyConservation = energyConservation;
  p.ImageSize = { 96, 72 };
  p.Exposure = 5.0;
  p.WavelengthRange = range;
  p.WavelengthStep = step;
  p.SpectralNodes = 0;
  const opal::RenderImage exact = renderer.render(volume, p);
  p.SpectralNodes = 16;
  const opal::RenderImage nodes = renderer.render(volume, p);
  const RelativeDifference d = relativeDifference(exact, nodes);
  std::ostringstream tableName;
  tableName << range[0] << "-" << range[1] << " nm by " << step << " nm" << (energyConservation ? ", energy conserved" : "");
  const std::string table = tableName.str();
  std::cout << "16 spectral nodes against every wavelength, " << table << ": mean " << 100 * d.Mean << "%, worst "
            << 100 * d.Max << "%" << std::endl;
  OPAL_CHECK(d.Mean <= allowed.Mean && d.Max <= allowed.Max, "16 spectral nodes agree with every wavelength (" + table +
      "): mean " + std::to_string(100 * d.Mean) + "% <= " + std::to_string(100 * allowed.Mean) + "%, worst " +
      std::to_string(100 * d.Max) + "% <= " + std::to_string(100 * allowed.Max) + "%");
}

void checkSpectralNodes(opaltest::SceneRenderer& renderer)
{
  opal::ModelParameters model; // fig12's domains on a coarser grid
  model.Dimensions = { 80, 40, 100 };
  const auto volume = opal::buildVolume(model);
  checkSpectralNodes(renderer, volume->renderVolume(), { 380.0, 780.0 }, 10.0);
  checkSpectralNodes(renderer, volume->renderVolume(), { 400.0, 700.0 }, 5.0);
}

// A thick body (scattering spheres of 120-180 nm at a volume fraction of
// 0.7): a short wavelength's node sum underflows to 0 within the stone, whose
// log once made the resampled image NaN. The nodes' image is finite and
// agrees with every wavelength's, less closely than fig12's body: its log G
// is far from linear in s where blue light dies within a voxel or two
// (measured on lavapipe: mean 0.07%, worst pixel 2.0%; allowed 0.2% and 3%).
void checkThickBody(opaltest::SceneRenderer& renderer)
{
  opal::ModelParameters model;
  model.Dimensions = { 80, 40, 100 };
  model.ScatteringDiameterRange = { 120.0, 180.0 };
  model.ScatteringVolumeFraction = 0.7;
  const auto volume = opal::buildVolume(model);
  checkSpectralNodes(renderer, volume->renderVolume(), { 380.0, 780.0 }, 10.0, { 2e-3, 3e-2 });
}

// A body that absorbs red (mu_a(550) (550/lambda)^p with p = -8, 2/mm at
// 550 nm: 33/mm at 780 nm, 0.1/mm at 380 nm): the longest wavelength's node,
// node 0, is the one that dies deep in the stone (the thick body's shortest
// does). The nodes' image agrees with every wavelength's as the thick body's
// does (measured on lavapipe: mean 0.19%, worst pixel 2.3%), with energy
// conservation too: its rounds restart the nodes at every crossing, so a
// round deep in the stone can hold blue light while node 0 is 0 (that
// round's light was once dropped: mean 0.70%, worst pixel 31%).
void checkRedAbsorbingBody(opaltest::SceneRenderer& renderer)
{
  opal::ModelParameters model;
  model.Dimensions = { 80, 40, 100 };
  model.BodyAbsorption = 2.0;
  model.BodyAbsorptionExponent = -8.0;
  const auto volume = opal::buildVolume(model);
  checkSpectralNodes(renderer, volume->renderVolume(), { 380.0, 780.0 }, 10.0, { 2e-3, 3e-2 });
  checkSpectralNodes(renderer, volume->renderVolume(), { 380.0, 780.0 }, 10.0, { 2e-3, 3e-2 }, true);
}

// The light scattered more than once, resampled from its four nodes at every
// round's end, keeps the blue nodes' light where node 0 is 0 (in the body
// that absorbs red, the rounds deep in the stone). With domains whose Bragg
// band lies below 380 nm (diameters 100-120 nm) energy conservation dims
// nothing and only splits the view path into rounds at the crossings: with
// every wavelength for the single scattering, whose sums are then linear in
// the rounds, that part of the image is the whole rays' (measured: mean
// 5e-8, worst 4e-7). The every-order part differs by the four nodes'
// resampling, a log-cubic in sqrt(s), done per round instead of once: mean
// 0.22% and worst pixel 2.2% for a clear body; in the red-absorbing body,
// whose rounds deep in the stone have a steep spectrum the four nodes do not
// follow, mean 0.78% (worst pixel 134%, in dim blue pixels, where the round
// brightens them by up to 15%). Dropping the rounds whose node 0 was 0 made
// the mean 2.1%. Held: the mean within 1%.
void checkScatteredLightRounds(opaltest::SceneRenderer& renderer)
{
  opal::ModelParameters model;
  model.Dimensions = { 80, 40, 100 };
  model.BodyAbsorption = 2.0;
  model.BodyAbsorptionExponent = -8.0;
  model.DomainDiameterRange = { 100.0, 120.0 };
  const auto volume = opal::buildVolume(model);
  opal::RenderParameters p;
  p.ImageSize = { 96, 72 };
  p.Exposure = 5.0;
  p.SpectralNodes = 0;
  p.ScatteringOrders = opal::ScatteringOrdersKind::All;
  const opal::RenderImage whole = renderer.render(volume->renderVolume(), p);
  p.EnergyConservation = true;
  const opal::RenderImage rounds = renderer.render(volume->renderVolume(), p);
  const RelativeDifference d = relativeDifference(whole, rounds);
  std::cout << "Every order in rounds against whole rays, red-absorbing body: mean " << 100 * d.Mean << "%, worst "
            << 100 * d.Max << "%" << std::endl;
  OPAL_CHECK(d.Mean <= 1e-2, "every order in rounds agrees with whole rays: mean " + std::to_string(100 * d.Mean) + "% <= 1%");
}

// A clear slab (no scattering, so no domain dims another) with `layers`
// horizontal domains one above another, each of its own plane spacing, seen
// from above: a vertical ray crosses every one.
opal::RenderImage renderLayers(opaltest::SceneRenderer& renderer, const std::vector<int>& layers)
{
  opaltest::SlabScene scene;
  opal::RenderVolume volume = scene.build();
  const int nx = scene.Dimensions[0], ny = scene.Dimensions[1], nz = scene.Dimensions[2];
  for (std::size_t d = 0; d < layers.size(); ++d)
  {
    const int j = 1 + 2 * layers[d]; // layers on every other voxel row
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i)
        scene.DomainField[static_cast<std::size_t>(i + nx * (j + ny * k))] = static_cast<std::int32_t>(d);
    volume.Domains.push_back({ { 0.0f, 1.0f, 0.0f }, static_cast<float>(130.0 + 12.0 * layers[d]) });
  }
  volume.DomainId = scene.DomainField.data();
  return renderer.render(volume, opaltest::slabView(17));
}

void checkCrossingRounds(opaltest::SceneRenderer& renderer)
{
  constexpr int Layers = 10; // more than the record's 8
  std::vector<int> all;
  for (int layer = 0; layer < Layers; ++layer)
  {
    all.push_back(layer);
  }
  const opal::RenderImage together = renderLayers(renderer, all);
  // The sum of the layers alone, each less the light's highlight (no domain).
  opal::RenderImage sum = renderLayers(renderer, {});
  const std::vector<float> highlight = sum.XYZ;
  for (int layer = 0; layer < Layers; ++layer)
  {
    const opal::RenderImage alone = renderLayers(renderer, { layer });
    for (std::size_t i = 0; i < sum.XYZ.size(); ++i)
    {
      sum.XYZ[i] += alone.XYZ[i] - highlight[i];
    }
  }
  const RelativeDifference d = relativeDifference(sum, together);
  OPAL_CHECK(d.Max <= 1e-4, "10 domains on one ray (two rounds of the crossing record) give the sum of each alone: "
    "worst " + std::to_string(100 * d.Max) + "%");
}
double meanLuminance(const opal::RenderImage& image)
{
  double sum = 0;
  for (std::size_t i = 1; i < image.XYZ.size(); i += 3)
  {
    sum += image.XYZ[i];
  }
  return sum / static_cast<double>(image.XYZ.size() / 3);
}

void checkPreview(opaltest::SceneRenderer& renderer)
{
  opal::ModelParameters model;
  model.Dimensions = { 80, 40, 100 };
  const auto volume = opal::buildVolume(model);
  opal::RenderParameters p;
  p.ImageSize = { 96, 72 };
  p.Exposure = 5.0;
  const opal::RenderImage final = renderer.render(volume->renderVolume(), p);
  p.Quality = opal::RenderQuality::Preview;
  const opal::RenderImage preview = renderer.render(volume->renderVolume(), p);
  OPAL_CHECK(preview.ImageSize == (std::array<int, 2>{ 48, 36 }) && preview.Wavelengths.size() == 21,
    "a preview renders 48 x 36 pixels at 21 wavelengths");
  const double change = meanLuminance(preview) / meanLuminance(final) - 1;
  OPAL_CHECK(std::fabs(change) < 0.03, "the preview's mean luminance is within 3% of the final image's: " +
      std::to_string(100 * change) + "%");
}
} // namespace

int TestOpalSpectralMarch(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  checkSpectralNodes(*renderer);
  checkThickBody(*renderer);
  checkRedAbsorbingBody(*renderer);
  checkScatteredLightRounds(*renderer);
  checkCrossingRounds(*renderer);
  checkPreview(*renderer);
  const auto messages = renderer->context().validationMessages();
  OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  return opaltest::finish("TestOpalSpectralMarch");
}
