// A Monte Carlo oracle for the body's light transport, independent of the
// product and of the quadrature reference renderer: it samples where the light
// scatters instead of marching, solves every intersection analytically, and
// estimates its own standard error, so that a test can tell a real
// disagreement from Monte Carlo noise. It shares no code with the rest of the
// project (only the standard library and glm), so that agreement with it means
// something.
//
// The scene (lengths mm, wavelengths nm):
// - a uniform medium filling the half-ellipsoid
//   x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1, y >= 0 (its base y = 0 a surface too);
// - Rayleigh scattering mu_s(lambda) = mu_s(550) (550/lambda)^4, the
//   isotropic phase function 1/(4 pi);
// - an isotropic point light, its strength chosen so that its unattenuated
//   irradiance at the apex (0, b, 0) is 1.
//
// Both tracers estimate each pixel's AREA mean (a box filter): every path
// starts on its own ray through a point drawn uniformly, stratified, over the
// pixel, and a ray that misses the medium contributes 0, so a pixel the
// silhouette crosses holds the covered share of its light.
//
// trace(): single scattering behind an index-matched boundary, no absorption
// (no refraction, no Fresnel, no surface reflection). A ray's radiance is
// the integral over its part inside the medium of
// mu_s/(4 pi) E(x) exp(-tau_light(x)) exp(-tau_view(x)) dt.
//
// traceAllOrders(): every order of scattering ("the milky body as light really
// crosses it"), the model of the product's renderer:
// - the view ray refracts into the medium (index mu, 1 outside) by Snell's law
//   and carries 1 - F, F the unpolarised Fresnel reflectance from outside; the
//   reflected part (the surface highlight) is left out;
// - inside, extinction mu_t = mu_s + mu_a, mu_a(lambda) = mu_a(550)
//   (550/lambda)^k; free flights are sampled with mu_t; a flight that reaches
//   the boundary is reflected back in with probability F (Fresnel from inside,
//   total internal reflection beyond the critical angle), else the path leaves
//   and ends (the point light cannot be seen directly);
// - at each scattering vertex x the weight takes the albedo mu_s/mu_t and the
//   light is estimated directly: weight / (4 pi) * E(x), with
//   E(x) = strength / r^2 * (1 - F(cos)) * exp(-mu_t * chord), where the
//   STRAIGHT segment from x to the light (the light is not refracted, the
//   paper's light model) leaves the medium after `chord` mm at angle cos to
//   the surface normal there; then the path scatters isotropically;
// - Russian roulette below weight 0.1 ends long paths without bias.
// With mu = 1, no absorption and maxOrder = 1 it estimates what trace() does.
//
// traceSlab(): the same transport (free flights, Fresnel and total internal
// reflection at the boundary, albedo, roulette) in an infinite slab, photons
// followed forward from a collimated beam, to validate that transport against
// the slab's transport equation.
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
  double RefractiveIndex = 1;       // of the medium (outside 1); traceAllOrders() only
  double Absorption550 = 0;         // mu_a at 550 nm (1/mm); traceAllOrders() only
  double AbsorptionExponent = 0;    // k in mu_a(lambda) = mu_a(550) (550/lambda)^k
};

// The camera of the product (its view angle, aspect and pixel grid), rows top to bottom.
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
  std::vector<std::uint8_t> Hit;     // per pixel: 1 where the ray through its centre meets the medium
  std::vector<double> Coverage;      // per pixel: the share of its paths whose ray met the medium (an
                                     // estimate of the covered share of its area: 0 or 1 away from the
                                     // silhouette, between at it)
};

// The unit direction from the eye through image point (x, y), in pixels from
// the image's top left corner (a pixel's centre at + 0.5).
std::array<double, 3> viewDirection(const View& view, double x, double y);

// Traces `samplesPerPixel` (>= 2) samples per pixel, each a ray through the
// pixel and a scattering distance on it, the same for every wavelength: 8
// independent replicates (2 below 16 samples) of floor(samplesPerPixel / 8)
// samples, each stratified over area and distance (a Latin hypercube).
// Radiance is the mean; StandardError comes from the replicates' spread.
// Each pixel has its own random stream drawn from the seed, so the same seed
// gives the same image. Throws std::invalid_argument on a degenerate scene,
// view or sample count, or on a scene with refraction or absorption (which it
// does not model).
Image trace(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed);

// Every order of scattering (docs: "the milky body as light really crosses it").
// `samplesPerPixel` (>= 2) paths per pixel and wavelength, each from its own
// point of the pixel's area (stratified): Radiance is their mean,
// StandardError their sample standard deviation over sqrt(samplesPerPixel)
// (conservative: the stratification's gain is not counted). Each pixel has its own random stream drawn from the
// seed, so the same seed gives the same image. maxOrder > 0 ends every path
// after that many scattering vertices (1: single scattering). Throws
// std::invalid_argument on a degenerate scene or view, an eye inside the
// medium, a refractive index below 1, negative absorption, fewer than 2
// samples or a negative maxOrder.
Image traceAllOrders(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed, int maxOrder = 0 /* 0 = unlimited; 1 = single scattering only */);

// StandardError: the largest of the standard errors of Reflectance,
// Transmittance, Absorbed and of their sum (which roulette makes 1 only on
// average, unless the albedo is 1).
struct SlabResult
{
  double Reflectance = 0, Transmittance = 0, Absorbed = 0, StandardError = 0;
};

// Collimated light at normal incidence on a slab of optical thickness tau (mu_t = 1/mm, thickness tau mm),
// single-scattering albedo `albedo`, index mu inside (1 outside): photons are followed forward (Fresnel at the
// entry: reflected photons count in Reflectance), every order; Reflectance/Transmittance: fraction of photons
// leaving through the lit / far face (Transmittance includes the unscattered beam). Throws
// std::invalid_argument unless tau > 0, 0 <= albedo <= 1, 1 <= mu < infinity and photons >= 2.
SlabResult traceSlab(double tau, double albedo, double refractiveIndex, std::int64_t photons, std::uint64_t seed);

} // namespace opaltracer
