// Final frames integrate each pixel's area (docs/design.md §3.4): where an
// edge crosses a pixel (the stone's outline, a domain's edge, a steep slope)
// the pixel is the mean of PixelSamples^2 sub-rays on a regular grid, which
// are the centre rays of an image PixelSamples times finer. So, for 40 of
// fig12's domains at 0.2 mm in a smooth body (at 250 in grain nearly every
// opal pixel of so small an image is an edge pixel; index-matched: no
// highlight, whose own sampling TestOpalReferenceOracle holds), 96 x 72
// pixels against 384 x 288:
// - a refined pixel (one that differs from the one-ray render) is its block's
//   mean in XYZ, Spectrum and Radiance (the background's share by the missed
//   sub-rays), its Depth the block's nearest, its dominant wavelength one of
//   the block's;
// - every other pixel is its own centre ray, and no edge the select compares
//   crosses it: it is near its block's mean;
// - the image's mean is the finer image's, where one ray per pixel is not;
// - a preview keeps one ray per pixel, and an image piece refines its pixels
//   as the whole image does.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Width = 96, Height = 72, Samples = 4;

opal::RenderParameters view(int scale, int pixelSamples)
{
  opal::RenderParameters p;
  p.ImageSize = { Width * scale, Height * scale };
  p.PixelSamples = pixelSamples;
  p.RefractiveIndex = 1.0; // no highlight
  p.Background = { 0.2, 0.2, 0.2 };
  p.Exposure = 1.0;
  p.WriteSpectrum = true;
  return p;
}

// The mean over pixel (x, y)'s block of the finer image of `components` values per pixel.
double blockMean(const std::vector<float>& fine, int components, int component, int x, int y)
{
  double sum = 0;
  for (int j = 0; j < Samples; ++j)
    for (int i = 0; i < Samples; ++i)
    {
      const auto p = static_cast<std::size_t>((Samples * y + j) * Width * Samples + Samples * x + i);
      sum += fine[p * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
    }
  return sum / (Samples * Samples);
}

// The largest |difference| of a pixel's values from its block's mean, over
// the scale `reference` (the image's brightest value of the kind).
double blockDifference(const std::vector<float>& coarse, const std::vector<float>& fine, int components, int x, int y,
  double reference)
{
  double worst = 0;
  const auto p = static_cast<std::size_t>(y * Width + x);
  for (int c = 0; c < components; ++c)
  {
    const double value = coarse[p * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)];
    worst = std::max(worst, std::fabs(value - blockMean(fine, components, c, x, y)) / reference);
  }
  return worst;
}

struct BlockChecks
{
  int Refined = 0, RefinedOff = 0, DepthOff = 0, DominantOff = 0, Others = 0, OthersOff = 0;
  double WorstRefined = 0, WorstOther = 0;
};

// Pixel (x, y)'s Depth against its block's nearest, its dominant wavelength against the block's.
void checkNearestAndDominant(const opal::RenderImage& coarse, const opal::RenderImage& fine, int x, int y, BlockChecks& c)
{
  const auto p = static_cast<std::size_t>(y * Width + x);
  double nearest = 0;
  bool dominantFound = coarse.DominantBraggWavelength[p] == 0;
  for (int j = 0; j < Samples; ++j)
    for (int i = 0; i < Samples; ++i)
    {
      const auto q = static_cast<std::size_t>((Samples * y + j) * Width * Samples + Samples * x + i);
      if (fine.Depth[q] > 0)
        nearest = nearest > 0 ? std::min<double>(nearest, fine.Depth[q]) : fine.Depth[q];
      dominantFound = dominantFound || std::fabs(fine.DominantBraggWavelength[q] - coarse.DominantBraggWavelength[p]) < 0.01;
    }
  c.DepthOff += std::fabs(coarse.Depth[p] - nearest) > 1e-4 * std::max(nearest, 1.0);
  c.DominantOff += !dominantFound;
}

BlockChecks compareBlocks(const opal::RenderImage& area, const opal::RenderImage& centres, const opal::RenderImage& fine)
{
  const int bins = static_cast<int>(area.Wavelengths.size());
  const double brightY = *std::max_element(fine.XYZ.begin(), fine.XYZ.end());
  const double brightBin = *std::max_element(fine.Spectrum.begin(), fine.Spectrum.end());
  BlockChecks c;
  for (int y = 0; y < Height; ++y)
    for (int x = 0; x < Width; ++x)
    {
      const auto p = static_cast<std::size_t>(y * Width + x);
      const bool refined = !std::equal(area.XYZ.begin() + 3 * p, area.XYZ.begin() + 3 * p + 3, centres.XYZ.begin() + 3 * p);
      const double colour = std::max(blockDifference(area.XYZ, fine.XYZ, 3, x, y, brightY),
        blockDifference(area.Radiance, fine.Radiance, 3, x, y, brightY));
      if (!refined) // a single bin of a pixel left with one ray moves with the Bragg band across it: colour only
      {
        const double d = colour;
        c.WorstOther = std::max(c.WorstOther, d);
        c.Others += centres.Depth[p] > 0;
        c.OthersOff += d > 0.02;
        continue;
      }
      const double d = std::max(colour, blockDifference(area.Spectrum, fine.Spectrum, bins, x, y, brightBin));
      ++c.Refined;
      c.WorstRefined = std::max(c.WorstRefined, d);
      c.RefinedOff += d > 1e-4;
      checkNearestAndDominant(area, fine, x, y, c);
    }
  return c;
}

double meanY(const opal::RenderImage& image)
{
  double sum = 0;
  for (std::size_t i = 1; i < image.XYZ.size(); i += 3)
    sum += image.XYZ[i];
  return sum / static_cast<double>(image.XYZ.size() / 3);
}

void checkAreaMeans(opaltest::SceneRenderer& renderer, const opal::RenderVolume& volume)
{
  const opal::RenderImage area = renderer.render(volume, view(1, Samples));
  const opal::RenderImage centres = renderer.render(volume, view(1, 1));
  const opal::RenderImage fine = renderer.render(volume, view(Samples, 1));
  const BlockChecks c = compareBlocks(area, centres, fine);
  const double fineY = meanY(fine), areaMean = meanY(area) / fineY - 1, centreMean = meanY(centres) / fineY - 1;
  std::cout << c.Refined << " of " << Width * Height << " pixels refined; refined against their blocks: worst "
            << c.WorstRefined << " of the brightest Y (" << c.RefinedOff << " beyond 1e-4), depth " << c.DepthOff
            << " and dominant wavelength " << c.DominantOff << " off; the others: worst " << c.WorstOther << ", "
            << c.OthersOff << " of " << c.Others << " beyond 0.02"
            << "; image mean " << 100 * areaMean << "% (one ray per pixel " << 100 * centreMean << "%)" << std::endl;
  OPAL_CHECK(c.Refined > Width + Height, "the outline's and the domains' edge pixels are refined");
  OPAL_CHECK(c.RefinedOff == 0, "each refined pixel is its block's mean in XYZ, Radiance and Spectrum");
  OPAL_CHECK(c.DepthOff == 0, "a refined pixel's Depth is its nearest sub-ray's");
  OPAL_CHECK(c.DominantOff == 0, "a refined pixel's dominant wavelength is one of its sub-rays'");
  // What the select does not see: a domain's edge where the neighbours' centre
  // rays cross the same first domain and draw their brightest diffraction
  // from the same one, a deeper domain differing (measured: 1 of 985 opal
  // pixels beyond 2% of the brightest Y, at 9.1%).
  OPAL_CHECK(c.WorstOther < 0.15 && c.OthersOff <= c.Others / 200,
    "no edge the select compares crosses a pixel left with one ray: it is near its block's mean");
  OPAL_CHECK(std::fabs(areaMean) < 0.002, "the image's mean is the finer image's");
}

// A preview keeps one ray per pixel; a piece of the image refines as the whole.
void checkPreviewAndPieces(opaltest::SceneRenderer& renderer, const opal::RenderVolume& volume)
{
  opal::RenderParameters preview = view(2, Samples);
  preview.Quality = opal::RenderQuality::Preview;
  const opal::RenderImage refined = renderer.render(volume, preview);
  preview.PixelSamples = 1;
  OPAL_CHECK(refined.XYZ == renderer.render(volume, preview).XYZ, "a preview takes one ray per pixel");
  const opal::RenderImage whole = renderer.render(volume, view(1, Samples));
  opal::RenderParameters piece = view(1, Samples);
  piece.ImageRegion = { 29, 17, 20, 17 };
  const opal::RenderImage part = renderer.render(volume, piece);
  bool same = true;
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c)
        same = same && part.XYZ[static_cast<std::size_t>(3 * (y * 20 + x) + c)] ==
            whole.XYZ[static_cast<std::size_t>(3 * ((y + 17) * Width + x + 29) + c)];
  OPAL_CHECK(same, "a piece of the image equals the whole image there, edge pixels included");
}
} // namespace

int TestOpalPixelArea(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
    return opaltest::noDeviceReturnCode();
  opal::ModelParameters model; // 40 of fig12's domains on a 0.2 mm grid, in a body that varies over millimetres
  model.Dimensions = { 80, 40, 100 };
  model.DiameterCorrelationLength = 2.0;
  model.DomainCount = 40;
  const auto volume = opal::buildVolume(model);
  checkAreaMeans(*renderer, volume->renderVolume());
  checkPreviewAndPieces(*renderer, volume->renderVolume());
  return opaltest::finish("TestOpalPixelArea");
}
