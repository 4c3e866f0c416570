// The reference renderer: the paper's algorithm (§6) followed literally, as an
// independent oracle and speed baseline for the Vulkan renderer. For every
// wavelength separately it marches the view ray, and at every sample it
// marches towards the light for T_L (eq. 6, 7); Rayleigh per eq. 1 and 8,
// Bragg per eq. 4 and 9; Fresnel and Snell at the surface; CIE colour
// matching. Where docs/design.md §4 amends the paper it follows the amendment:
// 1/r^2 to the sample, the view transmittance at each step's midpoint, the
// 1/pi on diffraction, domains counted once per crossing, the box band
// averaged over each wavelength bin. Beyond the paper (§2.10): absorption,
// each voxel's mu_a(lambda) evaluated per wavelength, so extinction mu_s +
// mu_a on every path, and domain voxels that scatter and absorb.
//
// Straightforward rather than clever: pixels spread over threads, no code shared with
// the product, only the CIE tables (data files). Two modes: literal (the
// paper's sampling: one sample per voxel segment of the view ray, a march
// towards the light in voxel-length steps with nearest-voxel coefficients,
// for every wavelength) and converged (View::Converged: the light path's
// optical depth exact, the view path refined until the image stops
// changing, each pixel the mean over its area), the oracle the product is
// held to.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace opalreference
{

struct Scene
{
  std::array<int, 3> Dimensions{};
  std::array<double, 3> Origin{};  // centre of voxel (0, 0, 0), mm
  std::array<double, 3> Spacing{}; // mm
  std::vector<float> Scattering;   // mu_s(550) in 1/mm per voxel, x fastest
  std::vector<int> DomainId;       // -1 or an index into Domains
  std::vector<float> SurfaceDistance;
  std::vector<std::array<double, 4>> Domains; // lattice normal x y z, plane spacing d (nm)
  // Absorption (docs/design.md §2.10), empty for none: mu_a(550) in 1/mm and
  // the exponent p of mu_a(lambda) = mu_a(550) (550/lambda)^p, per voxel.
  std::vector<float> Absorption, AbsorptionExponent;
};

struct View
{
  int Width = 64, Height = 48;
  std::array<double, 3> Eye{ 0, 60, 0 }, FocalPoint{ 0, 0, 0 }, ViewUp{ 0, 0, -1 };
  double ViewAngle = 24;  // vertical, degrees
  std::array<double, 3> Light{ 0, 60, 0 };
  double LightRadius = 0.5;
  double RefractiveIndex = 1.45;
  double BraggBandwidth = 0.04;
  double DiffractionGain = 4;
  double LambdaMin = 380, LambdaMax = 780, LambdaStep = 10;
  int SpecularSamples = 4;
  // Converged mode: the light integrated exactly (every voxel cell of its
  // path, the smooth surface found on it), the view path's body samples
  // doubled per voxel segment until no pixel changes by more than
  // ConvergenceTolerance, the highlight's coverage of each pixel by adaptive
  // subdivision, ConvergedHighlightDepth levels (1/256 of a pixel) deep, and
  // each pixel the mean over its area (a box filter): split adaptively,
  // AreaDepth levels deep, where its corners' and centre's rays see
  // different surfaces or first domains or disagree beyond the tolerance
  // (the literal mode traces the pixels' centres).
  bool Converged = false;
  double ConvergenceTolerance = 2e-3;
  int MaxViewSubsteps = 64;
  int ConvergedHighlightDepth = 8;
  int AreaDepth = 3;
};

struct Image
{
  std::vector<double> XYZ;       // 3 per pixel, rows top to bottom (converged mode: the pixel's area mean)
  std::vector<double> Dominant;  // dominant Bragg wavelength of the pixel's centre ray (0: none)
  std::vector<std::uint8_t> Hit; // 1 where the pixel's centre ray meets the opal
  std::vector<double> CosIncidence; // cosine of the primary ray's incidence angle (0 where missed)
  std::vector<double> Highlight;    // the light's Fresnel highlight: the fraction of sub-rays, times F
  std::vector<std::uint8_t> Refined; // converged mode: 1 where the pixel's area was split (an edge crosses it)
  int ViewSubsteps = 1;             // body samples per voxel segment (converged mode: where it converged)
};

// Renders with the CIE tables read from `cieDirectory` (the product's data files).
Image render(const Scene& scene, const View& view, const std::string& cieDirectory);

} // namespace opalreference
