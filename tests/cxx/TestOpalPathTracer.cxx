// The body against an independent Monte Carlo path tracer
// (tests/reference/OpalPathTracer: analytic half-ellipsoid, free-flight
// sampling, its own standard error): a uniform Rayleigh half-ellipsoid behind
// an index-matched boundary (RefractiveIndex 1, Illuminant none), light and
// eye 60 mm above, per pixel at 450, 550 and 650 nm. The product sees the
// shape through its voxel grid (SurfaceDistance sampled every 0.2 mm, its
// zero read trilinearly), the tracer exactly: away from the silhouette they
// agree per pixel; the silhouette's pixels, whose rays graze the dome where
// it meets the base (below the grid's first layer of centres), see chords
// that the sampled surface shortens, so there the mean is held (measured -1.3, -1.7 and -2.0%; tolerance 3%),
// not each pixel (up to -47%).
#include "OpalHalfEllipsoid.h"
#include "OpalPathTracer.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr double Scattering550 = 0.34; // 1/mm, the paper's body
const std::array<double, 3> SemiAxes{ 8.0, 4.0, 10.0 };
const std::vector<double> Wavelengths{ 450.0, 550.0, 650.0 };

// The half-ellipsoid on a 0.2 mm grid just covering it, mu_s everywhere
// (the medium ends where SurfaceDistance turns positive).
struct EllipsoidScene
{
  std::vector<float> Scattering, Distance;
  std::vector<std::int32_t> Domain;

  opal::RenderVolume build()
  {
    opal::ModelParameters p;
    p.Dimensions = { 84, 22, 104 };
    p.PhysicalSize = { 16.8, 4.4, 20.8 };
    const opal::Grid grid = opal::Grid::fromParameters(p);
    const opal::HalfEllipsoid shape(SemiAxes);
    const auto count = static_cast<std::size_t>(grid.voxelCount());
    this->Scattering.assign(count, static_cast<float>(Scattering550));
    this->Domain.assign(count, -1);
    this->Distance.resize(count);
    for (int k = 0; k < p.Dimensions[2]; ++k)
      for (int j = 0; j < p.Dimensions[1]; ++j)
        for (int i = 0; i < p.Dimensions[0]; ++i)
          this->Distance[static_cast<std::size_t>(grid.linearIndex(i, j, k))] =
            static_cast<float>(shape.signedDistance(grid.position(i, j, k)));
    opal::RenderVolume volume;
    volume.Dimensions = p.Dimensions;
    volume.Origin = grid.Origin;
    volume.Spacing = grid.Spacing;
    volume.ScatteringCoefficient = this->Scattering.data();
    volume.DomainId = this->Domain.data();
    volume.SurfaceDistance = this->Distance.data();
    return volume;
  }
};

struct Agreement
{
  double ProductMean = 0, TracerMean = 0; // over the pixels both see the opal in
  double RimMean = 0, RimTracerMean = 0;  // over those with a neighbour that misses
  double WorstSigma = 0;                  // the largest |difference| / standard error away from the rim
  double WorstInner = 0;                  // the largest relative difference away from the rim
  double WorstRim = 0;
  int Pixels = 0, RimPixels = 0, HitMismatches = 0;
};

bool isRim(const opaltracer::Image& traced, int width, int height, int x, int y)
{
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
    {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= width || ny >= height || !traced.Hit[static_cast<std::size_t>(ny * width + nx)])
        return true;
    }
  return false;
}

Agreement compareAt(const opal::RenderImage& image, const opaltracer::Image& traced, std::size_t w, int width, int height)
{
  Agreement a;
  const std::size_t bins = image.Wavelengths.size();
  std::size_t bin = 0;
  while (bin < bins && std::fabs(image.Wavelengths[bin] - Wavelengths[w]) > 1e-3)
    ++bin;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      const auto p = static_cast<std::size_t>(y * width + x);
      const bool productHit = image.Depth[p] > 0;
      a.HitMismatches += productHit != (traced.Hit[p] != 0);
      if (!productHit || !traced.Hit[p])
        continue;
      const double product = image.Spectrum[p * bins + bin], tracer = traced.Radiance[p * Wavelengths.size() + w];
      a.ProductMean += product;
      a.TracerMean += tracer;
      ++a.Pixels;
      if (isRim(traced, width, height, x, y))
      {
        a.RimMean += product;
        a.RimTracerMean += tracer;
        ++a.RimPixels;
        a.WorstRim = std::max(a.WorstRim, std::fabs(product / tracer - 1));
        continue;
      }
      const double sigma = traced.StandardError[p * Wavelengths.size() + w];
      a.WorstSigma = std::max(a.WorstSigma, std::fabs(product - tracer) / sigma);
      a.WorstInner = std::max(a.WorstInner, std::fabs(product / tracer - 1));
    }
  return a;
}
} // namespace

int TestOpalPathTracer(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
    return opaltest::noDeviceReturnCode();
  EllipsoidScene scene;
  opal::RenderParameters p;
  p.ImageSize = { 64, 48 };
  p.RefractiveIndex = 1.0;
  p.Illuminant = opal::LightSpectrum::None;
  p.SpectralNodes = 0;
  p.WriteSpectrum = true;
  p.Exposure = 1.0;
  const opal::RenderImage image = renderer->render(scene.build(), p);
  opaltracer::Scene tracerScene{ SemiAxes, Scattering550, { 0.0, 60.0, 0.0 } };
  const opaltracer::Image traced = opaltracer::trace(tracerScene, opaltracer::View{}, Wavelengths, 1024, 7);
  for (std::size_t w = 0; w < Wavelengths.size(); ++w)
  {
    const Agreement a = compareAt(image, traced, w, 64, 48);
    const double mean = a.ProductMean / a.TracerMean - 1, rim = a.RimMean / a.RimTracerMean - 1;
    OPAL_CHECK(a.HitMismatches == 0, "the product and the tracer see the opal in the same pixels");
    OPAL_CHECK(std::fabs(mean) < 0.005, std::to_string(Wavelengths[w]) + " nm: mean radiance within 0.5% of the tracer's");
    OPAL_CHECK(a.WorstInner < 0.01, "away from the silhouette every pixel within 1% of the tracer");
    OPAL_CHECK(std::fabs(rim) < 0.03, "the silhouette's pixels within 3% of the tracer's on average");
    std::cout << Wavelengths[w] << " nm: mean radiance " << 100 * mean << "% against the tracer over " << a.Pixels
              << " pixels; rim (" << a.RimPixels << " pixels) " << 100 * rim << "%; worst inner pixel "
              << a.WorstSigma << " standard errors, " << 100 * a.WorstInner << "%; worst rim pixel " << 100 * a.WorstRim << "%; " << a.HitMismatches << " pixels hit by one only" << std::endl;
  }
  return opaltest::finish("TestOpalPathTracer");
}
