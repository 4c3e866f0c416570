// Host-side colorimetry: the sRGB colour of monochromatic light (for
// BraggColor and the "Visible spectrum" colour map), with the same XYZ ->
// linear sRGB matrix and hue-preserving tone map as the render's colour pass
// (shaders/spectrum_to_colour.comp).
#pragma once

#include <array>
#include <cstdint>

namespace opal
{

// XYZ (D65) to linear sRGB, IEC 61966-2-1.
std::array<double, 3> xyzToLinearSrgb(const std::array<double, 3>& xyz);

// Into [0, 1]^3 keeping the hue: negatives desaturated towards the luminance,
// over-bright colours scaled down as a whole.
std::array<double, 3> huePreservingToneMap(std::array<double, 3> rgb);

// The sRGB transfer function of one linear component in [0, 1].
double srgbEncode(double linear);

// The display colour of light of one wavelength (nm): its CIE 1931 colour in
// linear sRGB with the out-of-gamut negative channel clipped to 0, at the
// brightest the gamut allows between 400 and 700 nm; beyond, dimmed as the
// eye's sensitivity y-bar falls relative to 400 or 700 nm, so both ends of
// the spectrum fade to black as spectral light does (700-780 nm: dark red to
// black, not pink). Black outside the CIE tables (360-830 nm).
std::array<std::uint8_t, 3> wavelengthToSrgb8(double lambda);

} // namespace opal
