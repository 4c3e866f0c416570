// Coupled-wave Bragg reflectance of a colloidal crystal (docs/design.md
// §7.1): the permittivity of close-packed spheres as a mean plus
// Fourier components, and the reflectance of N coherent lattice layers of one
// plane family from first-order coupled-mode theory, s and p polarisation.
// Plain C++ shared by the renderer's host code, the Bragg map and the tests;
// the shaders port coupledModeReflectance as it is (see there).
#pragma once

#include <string>

namespace opal
{

// Spherical Bessel function j1(x) = (sin x - x cos x) / x^2.
double sphericalBesselJ1(double x);

// The Fourier transform of a sphere of radius r at |G| = x / r, over its value
// at G = 0: 3 j1(x) / x. 1 at x = 0; zero at x = 4.493, 7.725, ...
double sphereFormFactor(double x);

// Spheres of one index in a matrix of another, close-packed (docs/design.md §7.1).
struct ColloidalCrystal
{
  double SphereIndex = 1.45;                  // n_s, silica
  double MatrixIndex = 1.33;                  // n_m, water
  double Filling = 0.74048048969306104;       // f = pi / sqrt(18), close packing (~0.74)
};

// Empty if the crystal's indices are ones the render and the Bragg map both
// take ([1, 4), as RefractiveIndex), else the sentence naming the volume's
// field array (SphereRefractiveIndex or MatrixRefractiveIndex).
std::string crystalError(const ColloidalCrystal& crystal);

// eps_bar = f n_s^2 + (1 - f) n_m^2: the zeroth Fourier component.
double meanPermittivity(const ColloidalCrystal& crystal);

// n_bar = sqrt(eps_bar), the index that sets the Bragg wavelength in this model.
double meanIndex(const ColloidalCrystal& crystal);

// eps_G = 3 f (n_s^2 - n_m^2) j1(x) / x for a reciprocal-lattice vector G of
// the lattice, x = |G| r (r the sphere radius). Real and signed: the spheres
// sit on centres of inversion. FCC's structure factor (4 for the allowed hkl)
// is inside f.
double permittivityFourierComponent(const ColloidalCrystal& crystal, double x);

// One crossing of a domain by light of one wavelength, for one plane family and order.
struct CoupledWaveInput
{
  double WavelengthNm = 550.0;    // lambda, in vacuum
  double SpacingNm = 0.0;         // d, the family's plane spacing (order 1)
  double MeanIndex = 1.0;         // n_bar
  double FourierComponent = 0.0;  // eps_kG: of the order's reciprocal vector k G (x multiplied by k)
  double SinGlancing = 1.0;       // sin theta2, theta2 between the ray and the planes inside the crystal
  double Layers = 0.0;            // N = min(crossing thickness / d, CoherentLayers); may be fractional
  int Order = 1;                  // k
};

struct CoupledWaveReflectance
{
  double S = 0.0; // electric field along the planes
  double P = 0.0; // electric field in the plane of incidence
  double average() const { return 0.5 * (this->S + this->P); }
};

// R(lambda) of N layers for the input's family and order, docs/design.md §7.1.
CoupledWaveReflectance coupledWaveReflectance(const CoupledWaveInput& input);

// R of the input's family and order (s and p averaged) averaged over the
// bin of wavelengths centre +- width / 2 (nm) in closed form, for bins that span 1.5
// side-lobe periods or more (docs/design.md §7.2): per polarisation a band of
// peak tanh^2(kappa L) with the side lobes' phase average beside it, as wide
// as keeps the integral of R over delta at pi kappa tanh(kappa L). Exact in
// that integral; for the saturated band (kappa L >= 3) within 0.014 of the
// bin's true mean at 10 nm bins. input.WavelengthNm is not used.
double coupledWaveBandAverage(const CoupledWaveInput& input, double centre, double width);

// The reflectance of a grating of coupling kappa, detuning delta (both 1/nm)
// and thickness L (nm) from coupled-mode theory:
//   R = kappa^2 sinh^2(sL) / (s^2 cosh^2(sL) + delta^2 sinh^2(sL)), s^2 = kappa^2 - delta^2,
// with sinh -> sin past the band edge. Continuous at |delta| = kappa, where
// R = kappa^2 L^2 / (1 + kappa^2 L^2); never overflows.
double coupledModeReflectance(double kappa, double delta, double thickness);

} // namespace opal
