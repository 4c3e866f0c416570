#include "OpalCoupledWave.h"

#include "OpalOptics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace opal
{

namespace
{
// Below this x, (sin x - x cos x) / x^2 loses digits to cancellation (1e-12
// relative at 0.01) and x/3 (1 - x^2/10) is exact to 4e-11.
constexpr double BesselSeriesBelow = 1e-2;

// Below this y, tanh y / y and sin y / y divide 0 by 0 at y = 0 (and in float
// lose digits): 1 - y^2/3 and 1 - y^2/6 are exact there to about 1e-13.
constexpr double SeriesBelow = 1e-3;

// Rays closer than this to the planes (sin theta2) reflect nothing: kappa ~
// 1/sin theta2 has no finite limit there and the coupled-wave picture (slowly
// varying amplitudes along the plane normal) no longer holds.
constexpr double GrazingSin = 1e-6;

// tanh(20) is 1 in double; GLSL's tanh may be (e^y - e^-y)/(e^y + e^-y) = inf/inf beyond ~44 in float.
constexpr double TanhSaturates = 20.0;

// The integral from 0 to x (odd in x) over x = lambda - lambda_B of a band of
// half-width c with the side lobes' phase average beside it: 1 within |x| <= c
// (|delta| <= kappa there, c = kappa lambda / (pi k / d) at every lambda), and
// 1 - sqrt(1 - c^2/x^2) = 1 - s/|delta| beyond, whose integral from c is
// x - sqrt(x^2 - c^2) + c acos(c/x) - c, written against cancellation.
double bandIntegral(double x, double c)
{
  const double ax = std::fabs(x);
  if (ax <= c)
  {
    return x;
  }
  const double root = std::sqrt(ax * ax - c * c);
  return std::copysign(c * c / (ax + root) + c * std::acos(c / ax), x);
}

// y / tanh y, 1 at y = 0.
double overTanh(double y)
{
  return y < SeriesBelow ? 1.0 + y * y / 3.0 : y / std::tanh(std::min(y, TanhSaturates));
}
} // namespace

double sphericalBesselJ1(double x)
{
  if (std::fabs(x) < BesselSeriesBelow)
  {
    return x / 3.0 * (1.0 - x * x / 10.0);
  }
  return (std::sin(x) - x * std::cos(x)) / (x * x);
}

double sphereFormFactor(double x)
{
  if (std::fabs(x) < BesselSeriesBelow)
  {
    return 1.0 - x * x / 10.0;
  }
  return 3.0 * sphericalBesselJ1(x) / x;
}

std::string crystalError(const ColloidalCrystal& crystal)
{
  for (const auto& [name, index] : { std::pair<const char*, double>{ "SphereRefractiveIndex", crystal.SphereIndex },
         { "MatrixRefractiveIndex", crystal.MatrixIndex } })
  {
    if (!(index >= 1 && index < 4))
    {
      return std::string("The input volume's ") + name + " must lie in [1, 4), got " + std::to_string(index) + ".";
    }
  }
  return {};
}

double meanPermittivity(const ColloidalCrystal& c)
{
  return c.Filling * c.SphereIndex * c.SphereIndex + (1.0 - c.Filling) * c.MatrixIndex * c.MatrixIndex;
}

double meanIndex(const ColloidalCrystal& c)
{
  return std::sqrt(meanPermittivity(c));
}

double permittivityFourierComponent(const ColloidalCrystal& c, double x)
{
  const double contrast = c.SphereIndex * c.SphereIndex - c.MatrixIndex * c.MatrixIndex;
  return c.Filling * contrast * sphereFormFactor(x);
}

// Written as R = kappa^2 A^2 / (1 + b^2 A^2), one expression for both sides of
// the band edge (divide coupled-mode theory's forms by s^2 cosh^2(sL), resp. use
// cos^2 = 1 - sin^2 and delta^2 = s^2 + kappa^2):
//   inside the band  (s^2 = kappa^2 - delta^2 >= 0): A = tanh(sL) / s, b = delta;
//   outside the band (s^2 = delta^2 - kappa^2 > 0):  A = sin(sL) / s,  b = kappa.
// Both A tend to L at the edge, where R = kappa^2 L^2 / (1 + kappa^2 L^2). A is
// bounded (|A| <= L), so nothing overflows, and the branches are selects: the
// GLSL port keeps this form as it is.
double coupledModeReflectance(double kappa, double delta, double thickness)
{
  const double q2 = kappa * kappa - delta * delta;
  const double s = std::sqrt(std::fabs(q2));
  const double y = s * thickness;
  double a = 0.0;
  if (q2 >= 0.0)
  {
    a = y < SeriesBelow ? thickness * (1.0 - y * y / 3.0) : std::tanh(std::min(y, TanhSaturates)) / s;
  }
  else
  {
    a = y < SeriesBelow ? thickness * (1.0 - y * y / 6.0) : std::sin(y) / s;
  }
  const double b = q2 >= 0.0 ? delta : kappa;
  const double ka2 = kappa * kappa * a * a;
  return ka2 / (1.0 + b * b * a * a);
}

// docs/design.md §7.1. Order k reflects off the reciprocal vector k G: the planes
// act as a grating of period d / k, so lambda_B = 2 (d/k) n_bar sin theta2 and
// delta = (pi k / d)(lambda_B / lambda - 1), with the Fourier component of k G
// (the caller's, x multiplied by k). The crystal is as thick as before: L = N d.
// kappa = k0 eps_G / (2 n_bar sin theta2) is the s-wave coupling (fields
// parallel); the p fields make the angle 2 theta_n = 180 deg - 2 theta2, so
// kappa_p = kappa_s |cos 2 theta_n| = kappa_s |2 sin^2 theta2 - 1|.
CoupledWaveReflectance coupledWaveReflectance(const CoupledWaveInput& in)
{
  CoupledWaveReflectance r;
  // Written so that NaN inputs reflect nothing too.
  if (!(in.SinGlancing > GrazingSin && in.WavelengthNm > 0.0 && in.SpacingNm > 0.0 && in.Order >= 1 &&
        in.Layers > 0.0 && in.MeanIndex > 0.0))
  {
    return r;
  }
  const double sin2 = in.SinGlancing;
  const double period = in.SpacingNm / in.Order;
  const double braggNm = 2.0 * period * in.MeanIndex * sin2;
  const double delta = (Pi / period) * (braggNm / in.WavelengthNm - 1.0);
  const double kappaS = Pi * std::fabs(in.FourierComponent) / (in.MeanIndex * in.WavelengthNm * sin2);
  const double kappaP = kappaS * std::fabs(2.0 * sin2 * sin2 - 1.0);
  const double thickness = in.Layers * in.SpacingNm;
  r.S = coupledModeReflectance(kappaS, delta, thickness);
  r.P = coupledModeReflectance(kappaP, delta, thickness);
  return r;
}

// Coupled-mode theory's integrated reflectance: the integral of R over delta
// is pi kappa tanh(kappa L) for any kappa L (the saturated band's flat top 2
// kappa plus its side lobes' 2 kappa (pi/2 - 1); kinematically pi kappa^2 L).
// The closed form keeps that integral with a band of peak tanh^2(kappa L)
// (R's value at lambda_B) and half-width c / tanh(kappa L), c the saturated
// band's: for a thin crystal, a box as high as its sinc^2 peak and about as
// wide (1/L in delta against the half maximum's 1.39/L).
double coupledWaveBandAverage(const CoupledWaveInput& in, double centre, double width)
{
  if (!(in.SinGlancing > GrazingSin && in.SpacingNm > 0.0 && in.Order >= 1 && in.Layers > 0.0 &&
        in.MeanIndex > 0.0 && width > 0.0))
  {
    return 0.0;
  }
  const double period = in.SpacingNm / in.Order;
  const double braggNm = 2.0 * period * in.MeanIndex * in.SinGlancing;
  const double thickness = in.Layers * in.SpacingNm;
  const double couplingLength = Pi * std::fabs(in.FourierComponent) / (in.MeanIndex * in.SinGlancing); // kappa_s lambda
  const double unitHalfWidth = braggNm / ((Pi / period) * thickness); // c / (kappa L)
  double sum = 0.0;
  for (const double polarisation : { 1.0, std::fabs(2.0 * in.SinGlancing * in.SinGlancing - 1.0) })
  {
    const double kappaL = couplingLength * polarisation / braggNm * thickness;
    const double depth = std::tanh(std::min(kappaL, TanhSaturates));
    const double halfWidth = unitHalfWidth * overTanh(kappaL);
    const double x = centre - 0.5 * width - braggNm;
    sum += 0.5 * depth * depth * (bandIntegral(x + width, halfWidth) - bandIntegral(x, halfWidth)) / width;
  }
  return sum;
}

} // namespace opal
