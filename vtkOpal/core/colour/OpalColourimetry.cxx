#include "OpalColourimetry.h"

#include "OpalSpectralSampling.h"

#include <algorithm>
#include <cmath>

namespace opal
{

std::array<double, 3> xyzToLinearSrgb(const std::array<double, 3>& c)
{
  return { 3.2404542 * c[0] - 1.5371385 * c[1] - 0.4985314 * c[2],
    -0.9692660 * c[0] + 1.8760108 * c[1] + 0.0415560 * c[2],
    0.0556434 * c[0] - 0.2040259 * c[1] + 1.0572252 * c[2] };
}

std::array<double, 3> huePreservingToneMap(std::array<double, 3> rgb)
{
  const double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
  const double lowest = std::min({ rgb[0], rgb[1], rgb[2] });
  if (lowest < 0 && luminance > 0)
  {
    for (double& v : rgb)
    {
      v = luminance + (v - luminance) * (luminance / (luminance - lowest));
    }
  }
  for (double& v : rgb)
  {
    v = std::max(v, 0.0);
  }
  const double highest = std::max({ rgb[0], rgb[1], rgb[2] });
  if (highest > 1)
  {
    for (double& v : rgb)
    {
      v /= highest;
    }
  }
  return rgb;
}

double srgbEncode(double linear)
{
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::array<std::uint8_t, 3> wavelengthToSrgb8(double lambda)
{
  const std::array<double, 3> xyz{ cieColourMatching(0, lambda), cieColourMatching(1, lambda),
    cieColourMatching(2, lambda) };
  std::array<double, 3> rgb = xyzToLinearSrgb(xyz);
  for (double& v : rgb)
  {
    v = std::max(v, 0.0); // clipped to the gamut, not desaturated (which turns deep red pink)
  }
  const double highest = std::max({ rgb[0], rgb[1], rgb[2] });
  const double edge = lambda < 400.0 ? cieColourMatching(1, 400.0) : cieColourMatching(1, 700.0);
  const double brightness = lambda < 400.0 || lambda > 700.0 ? std::min(1.0, xyz[1] / edge) : 1.0;
  std::array<std::uint8_t, 3> bytes{ 0, 0, 0 };
  for (std::size_t c = 0; c < 3 && highest > 0; ++c)
  {
    bytes[c] = static_cast<std::uint8_t>(std::lround(255.0 * srgbEncode(brightness * rgb[c] / highest)));
  }
  return bytes;
}

} // namespace opal
