#include "OpalPathTracer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace opaltracer
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double Infinity = std::numeric_limits<double>::infinity();
using glm::dvec3;

dvec3 toVec(const std::array<double, 3>& a)
{
  return dvec3(a[0], a[1], a[2]);
}

// A range [Near, Far] of ray parameters; empty unless Near < Far, so that a
// tangent touch (Near == Far) counts as a miss: it has no length to scatter in.
struct Interval
{
  double Near = -Infinity;
  double Far = Infinity;

  bool empty() const { return !(this->Near < this->Far); }
};

Interval intersect(const Interval& a, const Interval& b)
{
  return { std::max(a.Near, b.Near), std::min(a.Far, b.Far) };
}

// The ray o + t d inside the full ellipsoid. Dividing by the semi-axes maps
// the ellipsoid onto the unit sphere and keeps t, leaving a quadratic in t.
Interval ellipsoidInterval(const dvec3& o, const dvec3& d, const dvec3& axes)
{
  const dvec3 os = o / axes, ds = d / axes;
  const double a = glm::dot(ds, ds);
  const double halfB = glm::dot(os, ds);
  const double c = glm::dot(os, os) - 1;
  const double discriminant = halfB * halfB - a * c;
  if (discriminant <= 0)
  {
    return { 0, 0 };
  }
  // The numerically stable pair of roots (no cancellation in -b +- sqrt):
  // q is never 0 here, as |q| >= sqrt(discriminant) > 0.
  const double q = -(halfB + std::copysign(std::sqrt(discriminant), halfB));
  const double r1 = q / a, r2 = c / q;
  return { std::min(r1, r2), std::max(r1, r2) };
}

// The ray o + t d on the upper side (y >= 0) of the base plane.
Interval upperHalfInterval(const dvec3& o, const dvec3& d)
{
  if (d.y == 0)
  {
    return o.y >= 0 ? Interval{} : Interval{ 0, 0 };
  }
  const double plane = -o.y / d.y;
  return d.y > 0 ? Interval{ plane, Infinity } : Interval{ -Infinity, plane };
}

// The half-ellipsoid is the intersection of two convex sets, so a ray meets
// it in at most one interval: the intersection of the two intervals.
Interval mediumInterval(const dvec3& o, const dvec3& d, const dvec3& axes)
{
  return intersect(ellipsoidInterval(o, d, axes), upperHalfInterval(o, d));
}

// The medium as the estimator needs it: geometry and light, in glm types.
struct Medium
{
  dvec3 Axes;
  dvec3 Light;
  double LightStrength; // |light - apex|^2: makes the irradiance at the apex 1
};

// The irradiance at x ignoring the medium, times the transmittance along the
// straight segment from x to the light (the medium is convex, so the part of
// that segment inside it is one interval).
double attenuatedIrradiance(const Medium& medium, const dvec3& x, double mu)
{
  const dvec3 toLight = medium.Light - x;
  const double distance2 = glm::dot(toLight, toLight);
  const double distance = std::sqrt(distance2);
  const Interval inside =
    intersect(mediumInterval(x, toLight / distance, medium.Axes), Interval{ 0, distance });
  const double chord = inside.empty() ? 0 : inside.Far - inside.Near;
  return medium.LightStrength / distance2 * std::exp(-mu * chord);
}

// Uniform on [0, 1) from the top 53 bits: unlike std::uniform_real_distribution
// this is the same on every standard library, so a seed means the same image.
double uniform01(std::mt19937_64& random)
{
  return static_cast<double>(random() >> 11) * (1.0 / 9007199254740992.0);
}

// The unbiased sample variance of values[begin, begin + count).
double sampleVariance(const std::vector<double>& values, std::size_t begin, std::size_t count)
{
  double mean = 0;
  for (std::size_t i = begin; i < begin + count; ++i)
  {
    mean += values[i];
  }
  mean /= static_cast<double>(count);
  double squares = 0;
  for (std::size_t i = begin; i < begin + count; ++i)
  {
    squares += (values[i] - mean) * (values[i] - mean);
  }
  return squares / static_cast<double>(count - 1);
}

// The standard error of the mean of one sample per stratum. The i.i.d.
// formula would overstate it many times over (stratifying removes most of the
// variance of a smooth integrand), and the exact stratified formula needs two
// samples per stratum; so adjacent strata are collapsed into pairs (a final
// three when N is odd) whose sample variance stands in for their strata's.
// Var(mean) = sum over groups of (g/N)^2 s_g^2 / g. Conservative in
// expectation: it also counts the variation across a pair that the finer
// strata remove.
double stratifiedStandardError(const std::vector<double>& values)
{
  const std::size_t n = values.size();
  double sum = 0;
  for (std::size_t begin = 0; begin < n;)
  {
    const std::size_t count = n - begin == 3 ? 3 : 2;
    sum += static_cast<double>(count) * sampleVariance(values, begin, count);
    begin += count;
  }
  return std::sqrt(sum) / static_cast<double>(n);
}

struct Estimate
{
  double Mean = 0;
  double StandardError = 0;
};

// Single scattering along the ray o + t d over `span`, for one mu_s. The
// scattering distance is drawn by free-flight sampling truncated to the span,
// p(t) = mu exp(-mu (t - t0)) / W with W = 1 - exp(-mu (t1 - t0)); dividing
// the integrand by p leaves W/(4 pi) E(x) exp(-tau_light): the view
// transmittance and mu_s cancel. u is stratified over the N samples.
Estimate estimateRay(const Medium& medium, const dvec3& o, const dvec3& d, const Interval& span,
  double mu, std::vector<double>& contributions, std::mt19937_64& random)
{
  const double w = -std::expm1(-mu * (span.Far - span.Near));
  if (!(w > 0))
  {
    return {}; // no scattering at all (mu_s = 0)
  }
  const std::size_t n = contributions.size();
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const double u = (static_cast<double>(k) + uniform01(random)) / static_cast<double>(n);
    const double t = span.Near - std::log1p(-u * w) / mu;
    contributions[k] = w / (4 * Pi) * attenuatedIrradiance(medium, o + t * d, mu);
    sum += contributions[k];
  }
  return { sum / static_cast<double>(n), stratifiedStandardError(contributions) };
}

struct Camera
{
  dvec3 Eye, Forward, Right, Up;
  double TanHalf, Aspect;
  int Width, Height;
};

Camera makeCamera(const View& view)
{
  if (view.Width < 1 || view.Height < 1 || !(view.ViewAngle > 0 && view.ViewAngle < 180))
  {
    throw std::invalid_argument("opaltracer: bad image size or view angle");
  }
  Camera camera;
  camera.Eye = toVec(view.Eye);
  camera.Forward = glm::normalize(toVec(view.FocalPoint) - camera.Eye);
  camera.Right = glm::normalize(glm::cross(camera.Forward, toVec(view.ViewUp)));
  camera.Up = glm::cross(camera.Right, camera.Forward);
  // NaN here means the eye is at the focal point or ViewUp is along the view.
  if (!std::isfinite(glm::dot(camera.Right, camera.Right) + glm::dot(camera.Up, camera.Up)))
  {
    throw std::invalid_argument("opaltracer: degenerate camera");
  }
  camera.TanHalf = std::tan(view.ViewAngle * Pi / 360);
  camera.Aspect = static_cast<double>(view.Width) / view.Height;
  camera.Width = view.Width;
  camera.Height = view.Height;
  return camera;
}

// The unit direction through the centre of pixel (px, py), rows top to bottom.
dvec3 rayDirection(const Camera& camera, int px, int py)
{
  const double nx = 2 * (px + 0.5) / camera.Width - 1;
  const double ny = 1 - 2 * (py + 0.5) / camera.Height;
  return glm::normalize(camera.Forward + nx * camera.TanHalf * camera.Aspect * camera.Right +
    ny * camera.TanHalf * camera.Up);
}

Medium makeMedium(const Scene& scene)
{
  const dvec3 axes = toVec(scene.SemiAxes);
  if (!(axes.x > 0 && axes.y > 0 && axes.z > 0) || !(scene.Scattering550 >= 0))
  {
    throw std::invalid_argument("opaltracer: bad semi-axes or scattering coefficient");
  }
  const dvec3 light = toVec(scene.Light);
  const dvec3 fromApex = light - dvec3(0, axes.y, 0);
  const double strength = glm::dot(fromApex, fromApex);
  // A light at the apex cannot have irradiance 1 there: the scale is undefined.
  if (!(strength > 0))
  {
    throw std::invalid_argument("opaltracer: the light is at the apex");
  }
  return { axes, light, strength };
}

std::vector<double> scatteringPerWavelength(const Scene& scene, const std::vector<double>& wavelengths)
{
  std::vector<double> mu;
  for (const double lambda : wavelengths)
  {
    if (!(lambda > 0))
    {
      throw std::invalid_argument("opaltracer: wavelengths must be positive");
    }
    mu.push_back(scene.Scattering550 * std::pow(550 / lambda, 4));
  }
  return mu;
}

} // namespace

Image trace(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed)
{
  if (samplesPerPixel < 2)
  {
    throw std::invalid_argument("opaltracer: the standard error needs 2 samples or more");
  }
  const Camera camera = makeCamera(view);
  const Medium medium = makeMedium(scene);
  const std::vector<double> mu = scatteringPerWavelength(scene, wavelengths);
  const std::size_t pixels = static_cast<std::size_t>(view.Width) * static_cast<std::size_t>(view.Height);
  Image image;
  image.Wavelengths = wavelengths;
  image.Radiance.assign(pixels * mu.size(), 0);
  image.StandardError.assign(pixels * mu.size(), 0);
  image.Hit.assign(pixels, 0);
  std::mt19937_64 random(seed);
  std::vector<double> contributions(static_cast<std::size_t>(samplesPerPixel));
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const dvec3 d = rayDirection(camera, px, py);
      // Only what lies in front of the eye: t >= 0.
      const Interval span = intersect(mediumInterval(camera.Eye, d, medium.Axes), Interval{ 0, Infinity });
      const auto pixel = static_cast<std::size_t>(py * view.Width + px);
      image.Hit[pixel] = span.empty() ? 0 : 1;
      for (std::size_t w = 0; w < mu.size() && !span.empty(); ++w)
      {
        const Estimate e = estimateRay(medium, camera.Eye, d, span, mu[w], contributions, random);
        image.Radiance[pixel * mu.size() + w] = e.Mean;
        image.StandardError[pixel * mu.size() + w] = e.StandardError;
      }
    }
  }
  return image;
}

} // namespace opaltracer
