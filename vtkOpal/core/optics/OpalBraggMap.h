// The Bragg-Snell wavelength each domain diffracts for a given light (and,
// with a mosaic spread, how strongly towards a given eye): paper eq. 3-5 and
// docs/design.md §3.1, evaluated per domain voxel or domain polygon.
#pragma once

#include <array>
#include <cstdint>

namespace opal
{

struct BraggMapSettings
{
  std::array<double, 3> LightPosition{ 0.0, 60.0, 0.0 }; // mm
  std::array<double, 3> EyePosition{ 0.0, 60.0, 0.0 };   // mm
  // The stone's turn under a fixed light and eye, as the render's ModelRotation
  // (degrees about x, then y, then z): light and eye are turned back into the
  // stone's frame (inStoneFrame), so a render and a Bragg map can share one
  // light and eye. braggMapAt reads the light and eye as in the stone's frame.
  std::array<double, 3> ModelRotation{ 0.0, 0.0, 0.0 };
  double RefractiveIndex = 1.45;
  int BraggOrder = 1;                                     // Bragg order k
  double MosaicSpread = 0.0;                           // degrees; 0 = off
  std::array<double, 2> VisibleRange{ 380.0, 780.0 };  // nm
  // n_bar of the coupled-wave model (docs/design.md §7.2): lambda_B = 2 d n_bar
  // sin theta2 / k with no refraction at the planes; 0: the paper's Bragg-Snell with RefractiveIndex.
  double CoupledWaveMeanIndex = 0.0;
};

struct BraggMapValue
{
  double Wavelength = 0;                  // nm, lambda_B
  double Visible = 0;                     // 1 inside the visible range (times the mosaic weight), else 0
  std::array<std::uint8_t, 3> Colour{};   // sRGB of lambda_B, black if not visible
};

// The settings with the light and eye turned back by ModelRotation into the
// stone's frame (and no rotation left): turned once per map, not per domain.
BraggMapSettings inStoneFrame(const BraggMapSettings& settings);

// For a domain at `position` with lattice-plane normal `normal` and spheres
// of diameter `diameterNm`.
BraggMapValue braggMapAt(const std::array<double, 3>& position, const std::array<double, 3>& normal,
  double diameterNm, const BraggMapSettings& settings);

} // namespace opal
