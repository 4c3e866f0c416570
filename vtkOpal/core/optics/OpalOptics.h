// Closed-form optics of the model (paper eq. 1-5), plain C++ shared by the
// volume source, the renderer's host code and the tests.
#pragma once

#include <cmath>

namespace opal
{

constexpr double Pi = 3.14159265358979323846;

// Relative index of silica spheres in water, paper eq. 2.
constexpr double SilicaInWaterIndex = 1.55 / 1.33;

// Reference wavelength at which the volume stores the scattering coefficient.
constexpr double ReferenceWavelengthNm = 550.0;

// Rayleigh scattering coefficient in 1/mm, paper eq. 1, with the number
// density n = phi / (pi l^3 / 6) of spheres of diameter l at volume fraction phi.
inline double rayleighScatteringPerMm(double diameterNm, double volumeFraction, double wavelengthNm)
{
  const double m2 = SilicaInWaterIndex * SilicaInWaterIndex;
  const double polarisability = (m2 - 1.0) / (m2 + 2.0);
  const double lMm = diameterNm * 1e-6;
  const double lambdaMm = wavelengthNm * 1e-6;
  const double numberDensity = volumeFraction / (Pi * lMm * lMm * lMm / 6.0);
  const double l6 = std::pow(lMm, 6.0);
  return (2.0 * std::pow(Pi, 5.0) / 3.0) * numberDensity * polarisability * polarisability * l6 /
    std::pow(lambdaMm, 4.0);
}

// FCC (111) lattice-plane spacing for spheres of diameter l, paper eq. 3.
inline double fccPlaneSpacing(double diameterNm)
{
  return std::sqrt(2.0 / 3.0) * diameterNm;
}

// Longest diffracted wavelength, at normal incidence: 2 mu d (paper eq. 4, theta = 90 deg).
inline double braggLambdaMax(double diameterNm, double refractiveIndex)
{
  return 2.0 * refractiveIndex * fccPlaneSpacing(diameterNm);
}

// Shortest wavelength that leaves the domain without total reflection, paper eq. 5.
inline double braggLambdaMin(double lambdaMaxNm, double refractiveIndex)
{
  return lambdaMaxNm * std::sqrt(1.0 - 1.0 / (refractiveIndex * refractiveIndex));
}

// Bragg-Snell wavelength of order k for a glancing angle theta1 (radians)
// between the incident light and the lattice plane, outside the crystal:
// lambda = 2 d sqrt(mu^2 - cos^2 theta1) / k. Spans [lambdaMin, lambdaMax] for k = 1.
inline double braggSnellWavelength(double diameterNm, double refractiveIndex, double glancingAngle, int order = 1)
{
  const double c = std::cos(glancingAngle);
  return 2.0 * fccPlaneSpacing(diameterNm) *
    std::sqrt(refractiveIndex * refractiveIndex - c * c) / static_cast<double>(order);
}

// Unpolarised Fresnel reflectance from index 1 into index mu for the cosine of
// the incidence angle (paper §6.1); the host twin of opal_optics.glsl's.
inline double fresnelReflectance(double cosIncidence, double mu)
{
  const double c = std::fmin(std::fmax(cosIncidence, 0.0), 1.0);
  const double sinT2 = (1.0 - c * c) / (mu * mu);
  if (sinT2 >= 1.0)
  {
    return 1.0;
  }
  const double cosT = std::sqrt(1.0 - sinT2);
  const double rs = (c - mu * cosT) / (c + mu * cosT);
  const double rp = (mu * c - cosT) / (mu * c + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// The same reflectance met from inside the medium of index mu, for the cosine
// of the inside angle: 1 beyond the critical angle (total internal
// reflection), else the outside reflectance at the refracted angle (the two
// sides reflect alike, Stokes' relations).
inline double internalFresnelReflectance(double cosInside, double mu)
{
  const double c = std::fmin(std::fmax(cosInside, 0.0), 1.0);
  const double sinOutside2 = mu * mu * (1.0 - c * c);
  if (sinOutside2 >= 1.0)
  {
    return 1.0;
  }
  return fresnelReflectance(std::sqrt(1.0 - sinOutside2), mu);
}

} // namespace opal
