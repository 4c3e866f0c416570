// A Monte Carlo oracle for single scattering, independent of the product and
// of the quadrature reference renderer: it samples where the light scatters
// instead of marching, solves every intersection analytically, and estimates
// its own standard error, so that a test can tell a real disagreement from
// Monte Carlo noise. It shares no code with the rest of the project (only the
// standard library and glm), so that agreement with it means something.
//
// The scene (lengths mm, wavelengths nm):
// - a uniform medium filling the half-ellipsoid
//   x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1, y >= 0, with an index-matched boundary
//   (no refraction, no Fresnel, no surface reflection);
// - Rayleigh scattering mu_s(lambda) = mu_s(550) (550/lambda)^4, no
//   absorption, the isotropic phase function 1/(4 pi), single scattering;
// - an isotropic point light, its strength chosen so that its unattenuated
//   irradiance at the apex (0, b, 0) is 1.
// A pixel's radiance is the integral over the part of its view ray inside
// the medium of mu_s/(4 pi) E(x) exp(-tau_light(x)) exp(-tau_view(x)) dt.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace opaltracer
{

struct Scene
{
  std::array<double, 3> SemiAxes{}; // a, b, c (mm)
  double Scattering550 = 0;         // mu_s at 550 nm (1/mm)
  std::array<double, 3> Light{};    // position of the point light (mm)
};

// The camera of the product: pixel-centre rays, rows top to bottom.
struct View
{
  int Width = 64, Height = 48;
  std::array<double, 3> Eye{ 0, 60, 0 }, FocalPoint{ 0, 0, 0 }, ViewUp{ 0, 0, -1 };
  double ViewAngle = 24; // vertical, degrees
};

struct Image
{
  std::vector<double> Wavelengths;   // nm, as passed to trace()
  std::vector<double> Radiance;      // [pixel * Wavelengths.size() + w], pixel = py * Width + px
  std::vector<double> StandardError; // of each Radiance value, same layout
  std::vector<std::uint8_t> Hit;     // per pixel: 1 where the view ray meets the medium
};

// Traces `samplesPerPixel` (>= 2) stratified samples per pixel and wavelength;
// the same seed gives the same image. Throws std::invalid_argument on a
// degenerate scene, view or sample count.
Image trace(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed);

} // namespace opaltracer
