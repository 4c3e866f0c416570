// The uniform Rayleigh half-ellipsoid that the body's tests hold against the
// independent path tracer (tests/reference/OpalPathTracer): the product's
// voxel volume of it, and the agreement of the two at one of the tracer's
// wavelengths, both as pixel-area means (the tracer's by its own sampling of
// each pixel, the product's as rendered or box-averaged from a finer render):
// the image's total, each pixel away from the silhouette and the rings of the
// image by radius, the silhouette's included.
#pragma once

#include "OpalGrid.h"
#include "OpalHalfEllipsoid.h"
#include "OpalModelParameters.h"
#include "OpalPathTracer.h"
#include "OpalRenderImage.h"
#include "OpalRenderVolume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace opaltest
{
inline constexpr double Scattering550 = 0.34; // 1/mm, the paper's body
inline const std::array<double, 3> SemiAxes{ 8.0, 4.0, 10.0 };
inline const std::vector<double> Wavelengths{ 450.0, 550.0, 650.0 };

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

// The rings of the image: pixels by the normalised radius
// rho = sqrt((x/a)^2 + (z/c)^2) at which the ray through their centre meets
// the base plane y = 0. Seen from 60 mm above, the dome's silhouette (its
// tangent contour, 0.27 mm above the base) projects to rho = 1.002; a pixel
// is ~0.066 wide in rho across x and ~0.053 across z, so the last two rings
// hold the pixels the silhouette crosses and those just outside it.
inline const std::vector<double> RingEdges{ 0.0, 0.5, 0.7, 0.8, 0.9, 0.95, 1.0, 1.1 };

struct Ring
{
  double Inner = 0, Outer = 0;
  double Product = 0, Tracer = 0, Variance = 0; // sums over the ring's pixels; Variance: the tracer's
  int Pixels = 0;

  double difference() const { return this->Product / this->Tracer - 1; }
  double standardError() const { return std::sqrt(this->Variance) / this->Tracer; }
};

struct Agreement
{
  double ProductMean = 0, TracerMean = 0; // sums over every pixel compared (area means: silhouette pixels too)
  double RimMean = 0, RimTracerMean = 0;  // over the rim: pixels with a partly covered one among their 3 x 3
  double WorstSigma = 0;                  // the largest |difference| / standard error away from the rim
  double WorstInner = 0;                  // the largest relative difference away from the rim (over the
                                          // larger of the tracer's value and the floor, Agreement::Floor)
  double WorstRim = 0;                    // likewise on the rim, where the tracer's pixel is half covered or more
  int Pixels = 0, RimPixels = 0;
  int HitMismatches = 0; // pixels wholly inside (outside) the tracer's opal that the product misses (sees)
  std::vector<double> InnerDifferences; // |relative difference| of each pixel away from the rim
  std::vector<Ring> Rings;
  double Floor = 0; // 5% of the tracer's mean over the pixels it sees: a darker pixel's relative difference says little
};

// rho of the pixel (x, y), as RingEdges.
inline double ringRadius(const opaltracer::View& view, int x, int y)
{
  const std::array<double, 3> d = opaltracer::viewDirection(view, x + 0.5, y + 0.5);
  if (!(d[1] < 0))
    return 1e300;
  const double t = -view.Eye[1] / d[1];
  const double px = view.Eye[0] + t * d[0], pz = view.Eye[2] + t * d[2];
  return std::hypot(px / SemiAxes[0], pz / SemiAxes[2]);
}

// True where the tracer's pixel or one of its 8 neighbours is partly covered.
inline bool isRim(const opaltracer::Image& traced, int width, int height, int x, int y)
{
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
    {
      const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
      const double c = traced.Coverage[static_cast<std::size_t>(ny * width + nx)];
      if (c > 0 && c < 1)
        return true;
    }
  return false;
}

// The product's pixel-area means at one wavelength, and where it sees the
// opal, from an image rendered `factor` times finer each way (the same view
// angle): each k x k block box-averaged (the mean of its sub-pixels' centre
// rays), a pixel seen where any of its block is. factor 1: the image as rendered.
struct ProductPixels
{
  std::vector<double> Radiance;
  std::vector<bool> Hit;
};

inline ProductPixels productPixels(const opal::RenderImage& image, double wavelength, int factor)
{
  const std::size_t bins = image.Wavelengths.size();
  std::size_t bin = 0;
  while (bin < bins && std::fabs(image.Wavelengths[bin] - wavelength) > 1e-3)
    ++bin;
  const int fineWidth = image.ImageSize[0], width = fineWidth / factor, height = image.ImageSize[1] / factor;
  ProductPixels pixels{ std::vector<double>(static_cast<std::size_t>(width * height), 0.0),
    std::vector<bool>(static_cast<std::size_t>(width * height), false) };
  for (int y = 0; y < height * factor; ++y)
    for (int x = 0; x < width * factor; ++x)
    {
      const auto fine = static_cast<std::size_t>(y * fineWidth + x);
      const auto p = static_cast<std::size_t>((y / factor) * width + x / factor);
      pixels.Radiance[p] += image.Spectrum[fine * bins + bin] / (factor * factor);
      pixels.Hit[p] = pixels.Hit[p] || image.Depth[fine] > 0;
    }
  return pixels;
}

inline void addToRings(Agreement& a, double rho, double product, double tracer, double variance)
{
  for (Ring& ring : a.Rings)
    if (rho >= ring.Inner && rho < ring.Outer)
    {
      ring.Product += product;
      ring.Tracer += tracer;
      ring.Variance += variance;
      ++ring.Pixels;
    }
}

// One pixel of both into the agreement, `rim` as isRim.
inline void addPixel(Agreement& a, double product, double tracer, double sigma, double coverage, bool rim)
{
  const double difference = std::fabs(product - tracer) / std::max(tracer, a.Floor);
  a.ProductMean += product;
  a.TracerMean += tracer;
  ++a.Pixels;
  if (rim)
  {
    a.RimMean += product;
    a.RimTracerMean += tracer;
    ++a.RimPixels;
    if (coverage >= 0.5)
      a.WorstRim = std::max(a.WorstRim, difference);
    return;
  }
  if (coverage < 1)
    return; // wholly outside
  a.WorstSigma = std::max(a.WorstSigma, std::fabs(product - tracer) / sigma);
  a.WorstInner = std::max(a.WorstInner, difference);
  a.InnerDifferences.push_back(difference);
}

// The product's pixel-area means against the tracer's at the tracer's
// wavelength w (view: the tracer's, for the rings). Pixels with `skipped` set
// (if given) are left out.
inline Agreement compareAreas(const ProductPixels& product, const opaltracer::Image& traced, std::size_t w,
  const opaltracer::View& view, const std::vector<bool>& skipped = {})
{
  Agreement a;
  for (std::size_t r = 0; r + 1 < RingEdges.size(); ++r)
    a.Rings.push_back({ RingEdges[r], RingEdges[r + 1] });
  const std::size_t bins = traced.Wavelengths.size();
  int seen = 0;
  for (std::size_t p = 0; p < traced.Coverage.size(); ++p)
  {
    a.Floor += traced.Coverage[p] > 0 ? traced.Radiance[p * bins + w] : 0.0;
    seen += traced.Coverage[p] > 0;
  }
  a.Floor *= 0.05 / std::max(seen, 1);
  for (int y = 0; y < view.Height; ++y)
    for (int x = 0; x < view.Width; ++x)
    {
      const auto p = static_cast<std::size_t>(y * view.Width + x);
      const double coverage = traced.Coverage[p];
      if (!skipped.empty() && skipped[p])
        continue;
      a.HitMismatches += (coverage == 1 && !product.Hit[p]) || (coverage == 0 && product.Hit[p]);
      if (coverage == 0 && !product.Hit[p])
        continue;
      const double tracer = traced.Radiance[p * bins + w], sigma = traced.StandardError[p * bins + w];
      addPixel(a, product.Radiance[p], tracer, sigma, coverage, isRim(traced, view.Width, view.Height, x, y));
      addToRings(a, ringRadius(view, x, y), product.Radiance[p], tracer, sigma * sigma);
    }
  return a;
}

// The product's image as rendered (its default pixel filter) against the tracer.
inline Agreement compareAt(const opal::RenderImage& image, const opaltracer::Image& traced, std::size_t w,
  int width, int height, const std::vector<bool>& skipped = {})
{
  opaltracer::View view;
  view.Width = width;
  view.Height = height;
  return compareAreas(productPixels(image, Wavelengths[w], 1), traced, w, view, skipped);
}
} // namespace opaltest
