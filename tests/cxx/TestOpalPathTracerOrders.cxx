// The path tracer's every-order transport (tests/reference/OpalPathTracer:
// traceAllOrders, traceSlab) on its own, against results worked out here and
// sharing none of its code:
// - an index-matched slab under a collimated beam at normal incidence,
//   isotropic scattering: the diffuse reflectance and transmittance from a
//   deterministic solution of the slab's integral equation for the source
//   function (piecewise-constant Galerkin on N cells; N and 2N agree);
// - energy: at index 1.45 every photon leaves (albedo 1), or leaves or is
//   absorbed (albedo 0.9);
// - a slab that does not scatter, index 1.45: the incoherent sum of the
//   reflections between its faces, T = (1 - R0) / (1 + R0);
// - the half-ellipsoid, index-matched: its first order equals the single
//   scattering of trace() (an estimator of another kind: stratified, truncated
//   free flights), and every order brightens it (most in the blue, which
//   scatters most).
#include "OpalPathTracer.h"
#include "OpalTestHarness.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double EulerGamma = 0.57721566490153286061;
constexpr std::int64_t Photons = 200000;

// E1 by its power series up to 1 and its continued fraction beyond (both
// converge fast there: Abramowitz & Stegun 5.1.11, 5.1.22).
double expIntegral1(double x)
{
  if (x <= 1)
  {
    double sum = 0, power = 1; // power = (-x)^k / k!
    for (int k = 1; k < 40; ++k)
    {
      power *= -x / k;
      sum -= power / k;
    }
    return -EulerGamma - std::log(x) + sum;
  }
  // Modified Lentz evaluation of 1/(x+1- 1/(x+3- 4/(x+5- ...))).
  double b = x + 1, c = 1e300, d = 1 / b, fraction = d;
  for (int i = 1; i < 300; ++i)
  {
    const double a = -static_cast<double>(i) * i;
    b += 2;
    d = 1 / (a * d + b);
    c = b + a / c;
    fraction *= c * d;
    if (std::fabs(c * d - 1) < 1e-16)
    {
      break;
    }
  }
  return fraction * std::exp(-x);
}

// E3 from E1 by E_{n+1}(x) = (exp(-x) - x E_n(x)) / n.
double expIntegral3(double x)
{
  if (x == 0)
  {
    return 0.5;
  }
  const double e2 = std::exp(-x) - x * expIntegral1(x);
  return 0.5 * (std::exp(-x) - x * e2);
}

// Gaussian elimination without pivoting: the slab's matrix is strictly
// diagonally dominant (each row of the kernel integrates E1 over less than
// the whole line, so its sum times albedo/2 is below 1).
std::vector<double> solveLinearSystem(std::vector<double> matrix, std::vector<double> rhs)
{
  const std::size_t n = rhs.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    for (std::size_t i = k + 1; i < n; ++i)
    {
      const double factor = matrix[i * n + k] / matrix[k * n + k];
      for (std::size_t j = k; j < n; ++j)
      {
        matrix[i * n + j] -= factor * matrix[k * n + j];
      }
      rhs[i] -= factor * rhs[k];
    }
  }
  for (std::size_t i = n; i-- > 0;)
  {
    for (std::size_t j = i + 1; j < n; ++j)
    {
      rhs[i] -= matrix[i * n + j] * rhs[j];
    }
    rhs[i] /= matrix[i * n + i];
  }
  return rhs;
}

struct SlabFluxes
{
  double Reflectance = 0, Transmittance = 0;
};

// The source function of a slab of optical thickness b under unit flux at
// normal incidence: S(t) = w/(4 pi) e^-t + (w/2) int_0^b E1(|t - t'|) S(t') dt'.
// Piecewise constant on `cells` cells of width h, averaged over each cell
// (Galerkin): the double cell integrals of E1 are second differences of E3,
// K_ij = (E3((m-1) h) - 2 E3(m h) + E3((m+1) h)) / h, m = |i - j| > 0, off the
// diagonal and 2 - (1 - 2 E3(h)) / h on it. Galerkin keeps R + T = 1 exactly
// at albedo 1, whatever N. Returns the diffuse reflectance
// R = 2 pi sum S_j [E3(a_j) - E3(b_j)] and the transmittance with the direct beam.
SlabFluxes solveSlab(double b, double albedo, int cells)
{
  const auto n = static_cast<std::size_t>(cells);
  const double h = b / cells;
  std::vector<double> e3(n + 1), kernel(n);
  for (std::size_t k = 0; k <= n; ++k)
  {
    e3[k] = expIntegral3(static_cast<double>(k) * h);
  }
  kernel[0] = 2 - (1 - 2 * e3[1]) / h;
  for (std::size_t m = 1; m < n; ++m)
  {
    kernel[m] = (e3[m - 1] - 2 * e3[m] + e3[m + 1]) / h;
  }
  std::vector<double> matrix(n * n), source(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = 0; j < n; ++j)
    {
      matrix[i * n + j] = (i == j ? 1 : 0) - albedo / 2 * kernel[i > j ? i - j : j - i];
    }
    const double top = static_cast<double>(i) * h;
    source[i] = albedo / (4 * Pi) * (std::exp(-top) - std::exp(-top - h)) / h;
  }
  const std::vector<double> s = solveLinearSystem(std::move(matrix), std::move(source));
  SlabFluxes fluxes{ 0, std::exp(-b) };
  for (std::size_t j = 0; j < n; ++j)
  {
    fluxes.Reflectance += 2 * Pi * s[j] * (e3[j] - e3[j + 1]);
    fluxes.Transmittance += 2 * Pi * s[j] * (e3[n - 1 - j] - e3[n - j]);
  }
  return fluxes;
}

// Index-matched slabs: the tracer against the integral equation.
void checkIndexMatchedSlabs()
{
  const double cases[][2] = { { 0.5, 1 }, { 2, 1 }, { 2, 0.9 }, { 8, 1 } };
  for (const auto& c : cases)
  {
    const double tau = c[0], albedo = c[1];
    const SlabFluxes coarse = solveSlab(tau, albedo, 200), reference = solveSlab(tau, albedo, 400);
    std::ostringstream name;
    name << "tau " << tau << ", albedo " << albedo;
    const std::string label = name.str();
    OPAL_CHECK(std::fabs(coarse.Reflectance - reference.Reflectance) < 1e-4 &&
        std::fabs(coarse.Transmittance - reference.Transmittance) < 1e-4,
      label + ": the integral equation's R and T converged (N = 200 and 400 within 1e-4)");
    if (albedo == 1)
    {
      OPAL_CHECK(std::fabs(reference.Reflectance + reference.Transmittance - 1) < 1e-9,
        label + ": the integral equation conserves energy");
    }
    const opaltracer::SlabResult traced = opaltracer::traceSlab(tau, albedo, 1, Photons, 11);
    const double tolerance = 4 * traced.StandardError + 0.002;
    OPAL_CHECK(std::fabs(traced.Reflectance - reference.Reflectance) < tolerance,
      label + ": R as the integral equation's");
    OPAL_CHECK(std::fabs(traced.Transmittance - reference.Transmittance) < tolerance,
      label + ": T as the integral equation's");
    std::cout << label << ": R " << traced.Reflectance << " (integral equation " << reference.Reflectance << "), T "
              << traced.Transmittance << " (" << reference.Transmittance << "), standard error "
              << traced.StandardError << std::endl;
  }
}

// Index 1.45: Fresnel at the entry, partial and total reflection inside.
void checkEnergyConservation()
{
  const opaltracer::SlabResult lossless = opaltracer::traceSlab(2, 1, 1.45, Photons, 12);
  const double reflectedPhotons = lossless.Reflectance * static_cast<double>(Photons);
  OPAL_CHECK(std::fabs(reflectedPhotons - std::round(reflectedPhotons)) < 1e-6 &&
      std::fabs(lossless.Reflectance + lossless.Transmittance - 1) < 1e-12 && lossless.Absorbed == 0,
    "albedo 1, index 1.45: every photon leaves whole through one face");
  const opaltracer::SlabResult lossy = opaltracer::traceSlab(2, 0.9, 1.45, Photons, 13);
  const double total = lossy.Reflectance + lossy.Transmittance + lossy.Absorbed;
  OPAL_CHECK(std::fabs(total - 1) < 4 * lossy.StandardError, "albedo 0.9, index 1.45: R + T + A = 1");
  std::cout << "index 1.45, tau 2: albedo 1 R " << lossless.Reflectance << " T " << lossless.Transmittance
            << "; albedo 0.9 R " << lossy.Reflectance << " T " << lossy.Transmittance << " A " << lossy.Absorbed
            << ", R + T + A - 1 = " << total - 1 << " (standard error " << lossy.StandardError << ")" << std::endl;
}

// No scattering (albedo 0, and tau 1e-9 leaves a photon a 1e-9 chance per
// crossing to meet the medium at all): the beam bounces between the faces.
void checkNonScatteringSlab()
{
  const double mu = 1.45, r0 = (mu - 1) * (mu - 1) / ((mu + 1) * (mu + 1));
  const double expected = (1 - r0) / (1 + r0);
  const opaltracer::SlabResult traced = opaltracer::traceSlab(1e-9, 0, mu, Photons, 14);
  OPAL_CHECK(std::fabs(traced.Transmittance - expected) < 4 * traced.StandardError,
    "a clear slab of index 1.45 transmits (1 - R0) / (1 + R0)");
  std::cout << "clear slab, index 1.45: T " << traced.Transmittance << " (expected " << expected << ", standard error "
            << traced.StandardError << ")" << std::endl;
}

struct MeanRadiance
{
  double Mean = 0, StandardError = 0;
};

// Over the pixels that see the medium, at wavelength w.
MeanRadiance meanRadiance(const opaltracer::Image& image, std::size_t w)
{
  const std::size_t bins = image.Wavelengths.size();
  MeanRadiance m;
  int pixels = 0;
  for (std::size_t p = 0; p < image.Hit.size(); ++p)
  {
    if (image.Hit[p])
    {
      m.Mean += image.Radiance[p * bins + w];
      m.StandardError += image.StandardError[p * bins + w] * image.StandardError[p * bins + w];
      ++pixels;
    }
  }
  m.Mean /= pixels;
  m.StandardError = std::sqrt(m.StandardError) / pixels;
  return m;
}

// The mean over pixels and wavelength w of the squared difference of two
// images in combined standard errors: about 1 where they agree.
double meanSquaredZ(const opaltracer::Image& a, const opaltracer::Image& b, std::size_t w)
{
  const std::size_t bins = a.Wavelengths.size();
  double sum = 0;
  int pixels = 0;
  for (std::size_t p = 0; p < a.Hit.size(); ++p)
  {
    if (a.Hit[p])
    {
      const std::size_t i = p * bins + w;
      sum += std::pow((a.Radiance[i] - b.Radiance[i]) / std::hypot(a.StandardError[i], b.StandardError[i]), 2);
      ++pixels;
    }
  }
  return sum / pixels;
}

// The half-ellipsoid, index-matched: order 1 against trace(), in the mean and
// pixel by pixel (the mean squared z of n pixels stays below 1 + 4 sqrt(2/n):
// for the 60 pixels here, noise exceeds that with a chance of 4e-4), then
// every order.
void checkHalfEllipsoid()
{
  const std::vector<double> wavelengths{ 450.0, 550.0, 650.0 };
  const opaltracer::Scene scene{ { 8.0, 4.0, 10.0 }, 0.34, { 0.0, 60.0, 0.0 } };
  opaltracer::View view;
  view.Width = 16;
  view.Height = 12;
  const opaltracer::Image single = opaltracer::trace(scene, view, wavelengths, 256, 21);
  const opaltracer::Image firstOrder = opaltracer::traceAllOrders(scene, view, wavelengths, 4000, 22, 1);
  const opaltracer::Image allOrders = opaltracer::traceAllOrders(scene, view, wavelengths, 2000, 23);
  OPAL_CHECK(firstOrder.Hit == single.Hit && allOrders.Hit == single.Hit,
    "both tracers see the medium in the same pixels");
  const auto pixels = static_cast<double>(std::count(single.Hit.begin(), single.Hit.end(), 1));
  for (std::size_t w = 0; w < wavelengths.size(); ++w)
  {
    const MeanRadiance s = meanRadiance(single, w), first = meanRadiance(firstOrder, w),
                       all = meanRadiance(allOrders, w);
    const double squaredZ = meanSquaredZ(firstOrder, single, w);
    const std::string label = std::to_string(static_cast<int>(wavelengths[w])) + " nm: ";
    OPAL_CHECK(std::fabs(first.Mean - s.Mean) < 3 * std::hypot(first.StandardError, s.StandardError),
      label + "the first order's mean radiance equals trace()'s single scattering");
    OPAL_CHECK(squaredZ < 1 + 4 * std::sqrt(2 / pixels), label + "the first order equals trace() pixel by pixel");
    OPAL_CHECK(all.Mean - s.Mean > 3 * std::hypot(all.StandardError, s.StandardError),
      label + "every order is brighter than single scattering");
    std::cout << label << "mean radiance single " << s.Mean << " +- " << s.StandardError << ", first order "
              << first.Mean << " +- " << first.StandardError << " (mean squared z per pixel " << squaredZ << " over "
              << pixels << "), all orders " << all.Mean << " +- " << all.StandardError << "; single / all "
              << 100 * s.Mean / all.Mean << "%" << std::endl;
  }
}

// The same seed gives the same image; bad input is refused.
void checkDeterminismAndBadInput()
{
  opaltracer::Scene scene{ { 8.0, 4.0, 10.0 }, 0.34, { 0.0, 60.0, 0.0 } };
  scene.RefractiveIndex = 1.45;
  scene.Absorption550 = 0.05;
  opaltracer::View view;
  view.Width = 4;
  view.Height = 3;
  const std::vector<double> wavelengths{ 500.0 };
  const opaltracer::Image a = opaltracer::traceAllOrders(scene, view, wavelengths, 8, 5);
  const opaltracer::Image b = opaltracer::traceAllOrders(scene, view, wavelengths, 8, 5);
  OPAL_CHECK(a.Radiance == b.Radiance && a.StandardError == b.StandardError, "the same seed gives the same image");
  const auto refused = [&](opaltracer::Scene bad, int samples) {
    try
    {
      opaltracer::traceAllOrders(bad, view, wavelengths, samples, 5);
    }
    catch (const std::invalid_argument&)
    {
      return true;
    }
    return false;
  };
  opaltracer::Scene lowIndex = scene, negativeAbsorption = scene;
  lowIndex.RefractiveIndex = 0.9;
  negativeAbsorption.Absorption550 = -0.1;
  OPAL_CHECK(refused(lowIndex, 8) && refused(negativeAbsorption, 8) && refused(scene, 1),
    "an index below 1, negative absorption and a single sample are refused");
  OPAL_CHECK(!refused(scene, 8), "the good scene is accepted");
}
} // namespace

int TestOpalPathTracerOrders(int, char*[])
{
  checkIndexMatchedSlabs();
  checkEnergyConservation();
  checkNonScatteringSlab();
  checkHalfEllipsoid();
  checkDeterminismAndBadInput();
  return opaltest::finish("TestOpalPathTracerOrders");
}
