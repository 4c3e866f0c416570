// The uniform Rayleigh half-ellipsoid that the body's tests hold against the
// independent path tracer (tests/reference/OpalPathTracer): the product's
// voxel volume of it, and the per-pixel agreement of the two at one of the
// tracer's wavelengths (the silhouette's pixels apart, their rays graze the
// sampled surface).
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

struct Agreement
{
  double ProductMean = 0, TracerMean = 0; // over the pixels both see the opal in
  double RimMean = 0, RimTracerMean = 0;  // over those with a neighbour that misses
  double WorstSigma = 0;                  // the largest |difference| / standard error away from the rim
  double WorstInner = 0;                  // the largest relative difference away from the rim
  double WorstRim = 0;
  int Pixels = 0, RimPixels = 0, HitMismatches = 0;
  std::vector<double> InnerDifferences;   // |relative difference| of each pixel away from the rim
};

inline bool isRim(const opaltracer::Image& traced, int width, int height, int x, int y)
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

// Pixels with `skipped` set (if given) are left out.
inline Agreement compareAt(const opal::RenderImage& image, const opaltracer::Image& traced, std::size_t w,
  int width, int height, const std::vector<bool>& skipped = {})
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
      if (!skipped.empty() && skipped[p])
        continue;
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
      a.InnerDifferences.push_back(std::fabs(product / tracer - 1));
    }
  return a;
}
} // namespace opaltest
