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

struct Estimate
{
  double Mean = 0;
  double StandardError = 0;
};

// One single-scattering sample along the ray o + t d over `span`, for one
// mu_s, from u in [0, 1). The scattering distance is drawn by free-flight
// sampling truncated to the span, p(t) = mu exp(-mu (t - t0)) / W with
// W = 1 - exp(-mu (t1 - t0)); dividing the integrand by p leaves
// W/(4 pi) E(x) exp(-tau_light): the view transmittance and mu_s cancel.
double scatteringSample(const Medium& medium, const dvec3& o, const dvec3& d, const Interval& span, double mu, double u)
{
  const double w = -std::expm1(-mu * (span.Far - span.Near));
  if (!(w > 0))
  {
    return 0; // no scattering at all (mu_s = 0)
  }
  const double t = span.Near - std::log1p(-u * w) / mu;
  return w / (4 * Pi) * attenuatedIrradiance(medium, o + t * d, mu);
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

// The unit direction through image point (x, y), in pixels from the top
// left corner of the image (a pixel's centre is at + 0.5), rows top to bottom.
dvec3 rayDirection(const Camera& camera, double x, double y)
{
  const double nx = 2 * x / camera.Width - 1;
  const double ny = 1 - 2 * y / camera.Height;
  return glm::normalize(camera.Forward + nx * camera.TanHalf * camera.Aspect * camera.Right +
    ny * camera.TanHalf * camera.Up);
}

// The image point of sample k of n over pixel (px, py): the pixel is split
// into g x g equal cells, g = floor(sqrt(n)); sample k < g^2 lies uniformly
// in cell k, the rest uniformly anywhere in the pixel. Every cell holds one
// sample and each sample is uniform over its region, so the mean over the n
// samples of any function is an unbiased estimate of its mean over the
// pixel's area (a box filter), and the cells make it a stratified one.
glm::dvec2 pixelPoint(int px, int py, int k, int n, std::mt19937_64& random)
{
  const int g = static_cast<int>(std::sqrt(static_cast<double>(n)) + 1e-9);
  const double jx = uniform01(random), jy = uniform01(random);
  if (k >= g * g)
  {
    return { px + jx, py + jy };
  }
  return { px + (k % g + jx) / g, py + (k / g + jy) / g };
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

// --- Every order of scattering ---------------------------------------------

// The unpolarised Fresnel reflectance 0.5 (rs^2 + rp^2) of light meeting the
// interface from the side of index n1 at cosIncidence to the normal (either
// sign); 1 beyond the critical angle (total internal reflection).
double fresnelReflectance(double cosIncidence, double n1, double n2)
{
  if (n1 == n2)
  {
    return 0; // no interface; also spares grazing incidence its 0/0
  }
  const double cosI = std::min(std::fabs(cosIncidence), 1.0);
  const double sinT = n1 / n2 * std::sqrt(1 - cosI * cosI);
  if (sinT >= 1)
  {
    return 1;
  }
  const double cosT = std::sqrt(1 - sinT * sinT);
  const double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  const double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// Snell's law from index 1 into index mu for a ray d arriving from outside
// through a surface of outward normal n (d . n < 0): no total reflection this way.
dvec3 refractInward(const dvec3& d, const dvec3& n, double mu)
{
  const double cosI = -glm::dot(d, n);
  const double eta = 1 / mu;
  const double cosT = std::sqrt(1 - eta * eta * (1 - cosI * cosI));
  return glm::normalize(eta * d + (eta * cosI - cosT) * n);
}

// Where a ray leaves the body and the outward normal there.
struct Crossing
{
  double Distance;
  dvec3 Normal;
};

// What the transport needs of a convex body, so that the half-ellipsoid and
// the validation slab share one transport kernel: where a ray from a point
// inside (or on the boundary, after a reflection) leaves.
class Body
{
public:
  virtual ~Body() = default;
  virtual Crossing exitFrom(const dvec3& inside, const dvec3& direction) const = 0;
};

class HalfEllipsoidBody final : public Body
{
public:
  explicit HalfEllipsoidBody(const dvec3& axes)
    : Axes(axes)
  {
  }

  Crossing exitFrom(const dvec3& x, const dvec3& d) const override
  {
    const double dome = this->domeExit(x, d);
    // The base y = 0 bounds only a ray heading down; a point a rounding error
    // below it leaves at once.
    const double base = d.y < 0 ? std::max(-x.y / d.y, 0.0) : Infinity;
    if (base < dome)
    {
      return { base, dvec3(0, -1, 0) };
    }
    return { dome, this->domeNormal(x + dome * d) };
  }

  dvec3 domeNormal(const dvec3& p) const { return glm::normalize(p / (this->Axes * this->Axes)); }

private:
  // The far root of |(x + t d) / axes|^2 = 1. The point is inside, so c <= 0
  // but for rounding; clamping c keeps a point left just outside the dome by a
  // reflection from losing its chord (the roots then straddle 0, and the far
  // one is positive for a ray heading in, 0 for one heading out).
  double domeExit(const dvec3& x, const dvec3& d) const
  {
    const dvec3 xs = x / this->Axes, ds = d / this->Axes;
    const double a = glm::dot(ds, ds);
    const double halfB = glm::dot(xs, ds);
    const double c = std::min(glm::dot(xs, xs) - 1, 0.0);
    const double discriminant = halfB * halfB - a * c;
    if (!(discriminant > 0))
    {
      return 0; // tangent at a point of the boundary
    }
    const double q = -(halfB + std::copysign(std::sqrt(discriminant), halfB));
    return std::max(q / a, c / q);
  }

  dvec3 Axes;
};

// The slab 0 <= y <= Thickness, unbounded in x and z.
class SlabBody final : public Body
{
public:
  explicit SlabBody(double thickness)
    : Thickness(thickness)
  {
  }

  Crossing exitFrom(const dvec3& x, const dvec3& d) const override
  {
    if (d.y > 0)
    {
      return { std::max((this->Thickness - x.y) / d.y, 0.0), dvec3(0, 1, 0) };
    }
    if (d.y < 0)
    {
      return { std::max(-x.y / d.y, 0.0), dvec3(0, -1, 0) };
    }
    return { Infinity, dvec3(0, 1, 0) }; // along the faces: it scatters first
  }

private:
  double Thickness;
};

struct Transport
{
  double Extinction;      // mu_t (1/mm), > 0
  double Albedo;          // mu_s / mu_t
  double RefractiveIndex; // inside; 1 outside
};

struct Photon
{
  dvec3 Position, Direction;
  double Weight;
};

enum class Fate
{
  Scattered, // at a vertex, already given its new direction
  Escaped,   // out through the boundary
  Ended      // by Russian roulette
};

struct Event
{
  Fate What;
  dvec3 ExitNormal;      // Escaped: the outward normal where it left
  double AbsorbedWeight; // at a vertex: the weight the medium absorbed there
};

// Below this weight a path plays Russian roulette.
constexpr double RouletteWeight = 0.1;

dvec3 isotropicDirection(std::mt19937_64& random)
{
  const double z = 1 - 2 * uniform01(random);
  const double phi = 2 * Pi * uniform01(random);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return dvec3(r * std::cos(phi), r * std::sin(phi), z);
}

// A scattering vertex: the weight takes the albedo; a light path below
// RouletteWeight survives with probability weight / RouletteWeight and then
// carries RouletteWeight, which keeps every expectation and ends the long
// tails of faint paths. The survivor scatters isotropically.
Event scatter(const Transport& transport, Photon& photon, std::mt19937_64& random)
{
  const double absorbed = photon.Weight * (1 - transport.Albedo);
  photon.Weight *= transport.Albedo;
  if (photon.Weight < RouletteWeight)
  {
    if (uniform01(random) * RouletteWeight >= photon.Weight)
    {
      return { Fate::Ended, dvec3(0), absorbed };
    }
    photon.Weight = RouletteWeight;
  }
  photon.Direction = isotropicDirection(random);
  return { Fate::Scattered, dvec3(0), absorbed };
}

// The transport kernel: follows the photon to its next scattering vertex or
// out of the body. Free flights are drawn from mu_t; one that reaches the
// boundary first is reflected back in with the Fresnel probability from
// inside (certainly, beyond the critical angle), and a new flight is drawn
// from there (the exponential has no memory).
Event nextEvent(const Body& body, const Transport& transport, Photon& photon, std::mt19937_64& random)
{
  for (;;)
  {
    const Crossing exit = body.exitFrom(photon.Position, photon.Direction);
    const double flight = -std::log1p(-uniform01(random)) / transport.Extinction;
    if (flight < exit.Distance)
    {
      photon.Position += flight * photon.Direction;
      return scatter(transport, photon, random);
    }
    photon.Position += exit.Distance * photon.Direction;
    const double cosine = glm::dot(photon.Direction, exit.Normal);
    if (uniform01(random) >= fresnelReflectance(cosine, transport.RefractiveIndex, 1))
    {
      return { Fate::Escaped, exit.Normal, 0 };
    }
    photon.Direction -= 2 * cosine * exit.Normal;
  }
}

// The light's irradiance at x inside the medium: along the straight segment
// to it (the light is not refracted: the paper's light model), through the
// surface where that segment leaves (1 - F from outside) and attenuated by
// mu_t over its part inside; a light inside the medium has no surface between.
double irradianceThroughSurface(
  const Medium& medium, const HalfEllipsoidBody& body, const Transport& transport, const dvec3& x)
{
  const dvec3 toLight = medium.Light - x;
  const double distance2 = glm::dot(toLight, toLight);
  const double distance = std::sqrt(distance2);
  const dvec3 direction = toLight / distance;
  const Crossing exit = body.exitFrom(x, direction);
  const bool lightOutside = exit.Distance < distance;
  const double transmission =
    lightOutside ? 1 - fresnelReflectance(glm::dot(direction, exit.Normal), 1, transport.RefractiveIndex) : 1;
  return medium.LightStrength / distance2 * transmission *
    std::exp(-transport.Extinction * std::min(exit.Distance, distance));
}

// Where a view ray enters the medium, refracted, and the 1 - F it carries in.
struct EyeEntry
{
  bool Hit = false;
  dvec3 Point, Direction;
  double Transmission = 0;
};

EyeEntry enterMedium(const HalfEllipsoidBody& body, const dvec3& axes, const dvec3& eye, const dvec3& d, double mu)
{
  const Interval dome = ellipsoidInterval(eye, d, axes), upper = upperHalfInterval(eye, d);
  const Interval span = intersect(intersect(dome, upper), Interval{ 0, Infinity });
  if (span.empty())
  {
    return {};
  }
  const dvec3 point = eye + span.Near * d;
  // The later of the two entries is the medium's: the base where the ray
  // crosses the plane after entering the ellipsoid.
  const dvec3 normal = upper.Near > dome.Near ? dvec3(0, -1, 0) : body.domeNormal(point);
  return { true, point, refractInward(d, normal, mu), 1 - fresnelReflectance(glm::dot(d, normal), 1, mu) };
}

// One path from the eye: its radiance, the light estimated at every
// scattering vertex up to maxOrder (0: all). Roulette comes before the
// estimate at a vertex; as it keeps the expected weight, the order is free.
double tracePath(const Medium& medium, const HalfEllipsoidBody& body, const Transport& transport,
  const EyeEntry& entry, int maxOrder, std::mt19937_64& random)
{
  Photon photon{ entry.Point, entry.Direction, entry.Transmission };
  double radiance = 0;
  for (int order = 1; maxOrder == 0 || order <= maxOrder; ++order)
  {
    if (nextEvent(body, transport, photon, random).What != Fate::Scattered)
    {
      break;
    }
    radiance += photon.Weight / (4 * Pi) * irradianceThroughSurface(medium, body, transport, photon.Position);
  }
  return radiance;
}

// The pixel's paths for one wavelength, each from its own point of the
// pixel's area (pixelPoint): the mean of their radiances (0 for a path whose
// ray misses the medium) and its standard error, the i.i.d. formula (which
// the area's stratification makes conservative). Adds to `hits` the paths
// whose ray met the medium.
Estimate estimatePixel(const Medium& medium, const HalfEllipsoidBody& body, const Transport& transport,
  const Camera& camera, int px, int py, int maxOrder, std::vector<double>& radiances, int& hits,
  std::mt19937_64& random)
{
  const int n = static_cast<int>(radiances.size());
  double sum = 0;
  for (int k = 0; k < n; ++k)
  {
    const glm::dvec2 point = pixelPoint(px, py, k, n, random);
    const EyeEntry entry = enterMedium(
      body, medium.Axes, camera.Eye, rayDirection(camera, point.x, point.y), transport.RefractiveIndex);
    hits += entry.Hit ? 1 : 0;
    double& radiance = radiances[static_cast<std::size_t>(k)];
    radiance = entry.Hit && transport.Albedo > 0 ? tracePath(medium, body, transport, entry, maxOrder, random) : 0;
    sum += radiance;
  }
  return { sum / n, std::sqrt(sampleVariance(radiances, 0, radiances.size()) / n) };
}

// mu_t and the albedo per wavelength; a wavelength that does not scatter has
// albedo 0 (and no radiance), even without absorption.
std::vector<Transport> transportPerWavelength(const Scene& scene, const std::vector<double>& wavelengths)
{
  if (!(scene.RefractiveIndex >= 1 && std::isfinite(scene.RefractiveIndex)) ||
    !(scene.Absorption550 >= 0 && std::isfinite(scene.Absorption550)) || !std::isfinite(scene.AbsorptionExponent))
  {
    throw std::invalid_argument("opaltracer: bad refractive index or absorption");
  }
  const std::vector<double> scattering = scatteringPerWavelength(scene, wavelengths);
  std::vector<Transport> transports;
  for (std::size_t w = 0; w < wavelengths.size(); ++w)
  {
    const double absorption = scene.Absorption550 * std::pow(550 / wavelengths[w], scene.AbsorptionExponent);
    const double extinction = scattering[w] + absorption;
    transports.push_back({ extinction, scattering[w] > 0 ? scattering[w] / extinction : 0, scene.RefractiveIndex });
  }
  return transports;
}

void requireEyeOutside(const dvec3& eye, const dvec3& axes)
{
  const dvec3 scaled = eye / axes;
  if (eye.y >= 0 && glm::dot(scaled, scaled) <= 1)
  {
    throw std::invalid_argument("opaltracer: the eye is inside the medium");
  }
}

// The seed of a pixel's own random stream (splitmix64's finaliser), so that
// the image does not depend on the order the pixels are traced in.
std::uint64_t mix(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

struct SlabTally
{
  double Reflected = 0, Transmitted = 0, Absorbed = 0;
};

// One photon of the collimated beam, from its entry at normal incidence
// (reflected there with the Fresnel probability) until it leaves or ends.
SlabTally followSlabPhoton(
  const SlabBody& slab, const Transport& transport, double entryReflectance, std::mt19937_64& random)
{
  SlabTally tally;
  if (uniform01(random) < entryReflectance)
  {
    tally.Reflected = 1;
    return tally;
  }
  Photon photon{ dvec3(0), dvec3(0, 1, 0), 1 };
  for (;;)
  {
    const Event event = nextEvent(slab, transport, photon, random);
    tally.Absorbed += event.AbsorbedWeight;
    if (event.What == Fate::Escaped)
    {
      (event.ExitNormal.y < 0 ? tally.Reflected : tally.Transmitted) = photon.Weight;
    }
    if (event.What != Fate::Scattered)
    {
      return tally;
    }
  }
}

// The sums a mean and its standard error need.
struct Moments
{
  double Sum = 0, Squares = 0;

  void add(double value)
  {
    this->Sum += value;
    this->Squares += value * value;
  }
  double mean(double n) const { return this->Sum / n; }
  double standardError(double n) const
  {
    const double variance = (this->Squares - this->Sum * this->Sum / n) / (n - 1);
    return std::sqrt(std::max(variance, 0.0) / n);
  }
};

} // namespace

namespace
{
// An image of the view's size with every pixel missed and every radiance 0.
Image blankImage(const View& view, const std::vector<double>& wavelengths)
{
  const std::size_t pixels = static_cast<std::size_t>(view.Width) * static_cast<std::size_t>(view.Height);
  Image image;
  image.Wavelengths = wavelengths;
  image.Radiance.assign(pixels * wavelengths.size(), 0);
  image.StandardError.assign(pixels * wavelengths.size(), 0);
  image.Hit.assign(pixels, 0);
  image.Coverage.assign(pixels, 0);
  return image;
}

// The integers 0 .. n-1 in a random order (Fisher-Yates on uniform01, so
// that a seed means the same order on every standard library).
std::vector<int> shuffled(int n, std::mt19937_64& random)
{
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    order[static_cast<std::size_t>(i)] = i;
  }
  for (int i = n - 1; i > 0; --i)
  {
    const auto j = static_cast<std::size_t>(uniform01(random) * (i + 1));
    std::swap(order[static_cast<std::size_t>(i)], order[j]);
  }
  return order;
}

// One replicate of a trace() pixel: n rays through stratified points of the
// pixel's area (pixelPoint), each with one scattering distance whose stratum
// of [0, 1) is shuffled against the area's cells, so that the two
// stratifications are independent (a Latin hypercube: each pair is uniform
// over area x distance, the estimate unbiased). A ray that misses the medium
// contributes 0. Adds each wavelength's mean over the n rays to `means` and
// returns how many rays met the medium.
int singleScatteringReplicate(const Camera& camera, const Medium& medium, const std::vector<double>& mu, int px,
  int py, int n, std::vector<double>& means, std::mt19937_64& random)
{
  const std::vector<int> strata = shuffled(n, random);
  int hits = 0;
  for (int k = 0; k < n; ++k)
  {
    const glm::dvec2 point = pixelPoint(px, py, k, n, random);
    const dvec3 d = rayDirection(camera, point.x, point.y);
    const double u = (strata[static_cast<std::size_t>(k)] + uniform01(random)) / n;
    // Only what lies in front of the eye: t >= 0.
    const Interval span = intersect(mediumInterval(camera.Eye, d, medium.Axes), Interval{ 0, Infinity });
    if (span.empty())
    {
      continue;
    }
    ++hits;
    for (std::size_t w = 0; w < mu.size(); ++w)
    {
      means[w] += scatteringSample(medium, camera.Eye, d, span, mu[w], u) / n;
    }
  }
  return hits;
}

// A trace() pixel: R independent replicates (8; 2 below 16 samples) of
// floor(samplesPerPixel / R) rays each. Radiance is the mean of their means;
// its standard error comes from their spread, which stays honest however
// much variance the stratification removes within each.
void traceSinglePixel(const Camera& camera, const Medium& medium, const std::vector<double>& mu, int px, int py,
  int samplesPerPixel, std::mt19937_64& random, Image& image)
{
  const int replicates = samplesPerPixel < 16 ? 2 : 8, n = samplesPerPixel / replicates;
  const auto pixel = static_cast<std::size_t>(py * camera.Width + px);
  std::vector<std::vector<double>> means(mu.size(), std::vector<double>(static_cast<std::size_t>(replicates), 0.0));
  std::vector<double> replicate(mu.size());
  int hits = 0;
  for (int r = 0; r < replicates; ++r)
  {
    std::fill(replicate.begin(), replicate.end(), 0.0);
    hits += singleScatteringReplicate(camera, medium, mu, px, py, n, replicate, random);
    for (std::size_t w = 0; w < mu.size(); ++w)
    {
      means[w][static_cast<std::size_t>(r)] = replicate[w];
    }
  }
  for (std::size_t w = 0; w < mu.size(); ++w)
  {
    double mean = 0;
    for (const double m : means[w])
    {
      mean += m / replicates;
    }
    image.Radiance[pixel * mu.size() + w] = mean;
    image.StandardError[pixel * mu.size() + w] = std::sqrt(sampleVariance(means[w], 0, means[w].size()) / replicates);
  }
  image.Coverage[pixel] = static_cast<double>(hits) / (replicates * n);
}
} // namespace

Image trace(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed)
{
  if (samplesPerPixel < 2)
  {
    throw std::invalid_argument("opaltracer: the standard error needs 2 samples or more");
  }
  if (scene.RefractiveIndex != 1 || scene.Absorption550 != 0)
  {
    throw std::invalid_argument("opaltracer: trace() models neither refraction nor absorption");
  }
  const Camera camera = makeCamera(view);
  const Medium medium = makeMedium(scene);
  const std::vector<double> mu = scatteringPerWavelength(scene, wavelengths);
  Image image = blankImage(view, wavelengths);
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const auto pixel = static_cast<std::size_t>(py * view.Width + px);
      const dvec3 centre = rayDirection(camera, px + 0.5, py + 0.5);
      image.Hit[pixel] = intersect(mediumInterval(camera.Eye, centre, medium.Axes), Interval{ 0, Infinity }).empty() ? 0 : 1;
      std::mt19937_64 random(mix(seed ^ mix(pixel)));
      traceSinglePixel(camera, medium, mu, px, py, samplesPerPixel, random, image);
    }
  }
  return image;
}

Image traceAllOrders(const Scene& scene, const View& view, const std::vector<double>& wavelengths,
  int samplesPerPixel, std::uint64_t seed, int maxOrder)
{
  if (samplesPerPixel < 2 || maxOrder < 0)
  {
    throw std::invalid_argument("opaltracer: need 2 samples or more and a maxOrder >= 0");
  }
  const Camera camera = makeCamera(view);
  const Medium medium = makeMedium(scene);
  const std::vector<Transport> transports = transportPerWavelength(scene, wavelengths);
  requireEyeOutside(camera.Eye, medium.Axes);
  const HalfEllipsoidBody body(medium.Axes);
  Image image = blankImage(view, wavelengths);
  std::vector<double> radiances(static_cast<std::size_t>(samplesPerPixel));
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const auto pixel = static_cast<std::size_t>(py * view.Width + px);
      image.Hit[pixel] = enterMedium(body, medium.Axes, camera.Eye, rayDirection(camera, px + 0.5, py + 0.5),
                           scene.RefractiveIndex).Hit ? 1 : 0;
      std::mt19937_64 random(mix(seed ^ mix(pixel)));
      int hits = 0;
      for (std::size_t w = 0; w < transports.size(); ++w)
      {
        const Estimate e =
          estimatePixel(medium, body, transports[w], camera, px, py, maxOrder, radiances, hits, random);
        image.Radiance[pixel * transports.size() + w] = e.Mean;
        image.StandardError[pixel * transports.size() + w] = e.StandardError;
      }
      image.Coverage[pixel] = transports.empty()
        ? 0.0
        : hits / (static_cast<double>(samplesPerPixel) * static_cast<double>(transports.size()));
    }
  }
  return image;
}

std::array<double, 3> viewDirection(const View& view, double x, double y)
{
  const dvec3 d = rayDirection(makeCamera(view), x, y);
  return { d.x, d.y, d.z };
}

SlabResult traceSlab(double tau, double albedo, double refractiveIndex, std::int64_t photons, std::uint64_t seed)
{
  if (!(tau > 0 && std::isfinite(tau)) || !(albedo >= 0 && albedo <= 1) ||
    !(refractiveIndex >= 1 && std::isfinite(refractiveIndex)) || photons < 2)
  {
    throw std::invalid_argument("opaltracer: bad slab thickness, albedo, refractive index or photon count");
  }
  const SlabBody slab(tau);
  const Transport transport{ 1, albedo, refractiveIndex };
  const double entryReflectance = fresnelReflectance(1, 1, refractiveIndex);
  std::mt19937_64 random(seed);
  Moments reflected, transmitted, absorbed, total;
  for (std::int64_t i = 0; i < photons; ++i)
  {
    const SlabTally tally = followSlabPhoton(slab, transport, entryReflectance, random);
    reflected.add(tally.Reflected);
    transmitted.add(tally.Transmitted);
    absorbed.add(tally.Absorbed);
    total.add(tally.Reflected + tally.Transmitted + tally.Absorbed);
  }
  const auto n = static_cast<double>(photons);
  SlabResult result;
  result.Reflectance = reflected.mean(n);
  result.Transmittance = transmitted.mean(n);
  result.Absorbed = absorbed.mean(n);
  result.StandardError = std::max({ reflected.standardError(n), transmitted.standardError(n),
    absorbed.standardError(n), total.standardError(n) });
  return result;
}

} // namespace opaltracer
