// Every parameter of the spectral render (paper §6-7, docs/design.md §3.2), with the
// paper's set-up as defaults: one D65 point light and the eye at the same
// point 60 mm above the base's centre, looking down. Plain data.
#pragma once

#include "OpalParameterRow.h"
#include "OpalRenderParameterTable.h"

#include <array>
#include <string>
#include <vector>

namespace opal
{

// The light's spectrum: D65 normalised to luminance 1 (sum of D65 y-bar
// dlambda = 1), or None: unit spectral irradiance, so the Spectrum output is
// radiance per unit source spectrum (for comparisons with other renderers).
enum class LightSpectrum : int
{
  D65 = 0,
  None = 1,
};

// Final renders the parameters as they are; Preview, for interaction, renders
// 1/PreviewScale of the width and height, 20 nm wavelength steps, 8 spectral nodes, a
// 2 x 2 highlight and one ray per pixel (withQuality), marches PreviewStepScale x the step and reads
// the light field per voxel, not trilinearly (docs/design.md §3.4).
enum class RenderQuality : int
{
  Final = 0,
  Preview = 1,
};

// The preview's march step over the final's: twice a voxel, so a ray takes
// one scattering sample per voxel it crosses (a voxel's chord is at most
// sqrt(3) voxels) instead of about 1.6 (docs/design.md §3.4).
constexpr double PreviewStepScale = 2.0;

// The Bragg reflection of a domain crossing (docs/design.md §7.2): the
// paper's box band of gain G, or the coupled-wave reflectance of the lattice
// layers into a normalised lobe about the mirror direction.
enum class BraggModelKind : int
{
  Paper = 0,
  CoupledWave = 1,
};

// Which lattice planes reflect (docs/design.md §7.2): the (111) stacking
// planes (the paper's), or all 13 families of the FCC lattice (orders k while
// lambda_B >= the shortest rendered wavelength).
enum class LatticePlaneSet : int
{
  Stacking111 = 0,
  Fcc = 1,
};

// The orders of scattering in the body (docs/design.md §3.10): the paper's
// single scattering, or every order (the light scattered more than once, a
// field per light). Volume: the volume's (the paper's figures single, every
// other preset and a custom volume all); resolveFrame decides it.
enum class ScatteringOrdersKind : int
{
  Volume = 0,
  Single = 1,
  All = 2,
};

// MosaicSpread's value in the coupled-wave model when MosaicSpread is 0
// (degrees): a lobe must have a width (docs/design.md §7.2).
constexpr double CoupledWaveDefaultSpread = 3.0;
// The largest CoherentLayers: tanh^2(kappa L) is 1 in float long before.
constexpr int MaxCoherentLayers = 100000;

struct RenderParameters
{
  std::array<int, 2> ImageSize{ 640, 480 };            // pixels
  std::array<int, 4> ImageRegion{ 0, 0, -1, -1 };      // x0, y0, width, height (<= 0: to the edge)
  std::array<double, 3> EyePosition{ 0.0, 60.0, 0.0 }; // mm
  std::array<double, 3> FocalPoint{ 0.0, 0.0, 0.0 };   // mm
  std::array<double, 3> ViewUp{ 0.0, 0.0, -1.0 };      // image up: the opal's long axis z runs vertically
  double ViewAngle = 24.0;                             // vertical, degrees
  std::array<double, 3> LightPosition{ 0.0, 60.0, 0.0 }; // mm
  double LightRadius = 0.5;                            // mm: a 1 mm light
  std::array<double, 3> PresetRotation{ 0.0, 0.0, 0.0 }; // the preset's placement of the stone (fig13: 5 deg
                                                       // about x), degrees about x, then y, then z; first
  std::array<double, 3> ModelRotation{ 0.0, 0.0, 0.0 }; // a further turn of the stone, same convention
  std::array<double, 2> WavelengthRange{ 380.0, 780.0 }; // nm
  double WavelengthStep = 10.0;                        // nm: 41 wavelengths
  double RefractiveIndex = 1.45;                       // mu
  double BraggBandwidth = 0.04;                        // relative full width of the band B
  double DiffractionGain = 4.0;                        // G: the paper's doubled amplitude (§5)
  int BraggOrders = 1;                                 // k = 1..BraggOrders (paper: 1)
  double MosaicSpread = 0.0;                           // degrees; 0 = off, as in the paper
  double Exposure = 0.0;                               // 0: automatic (body's median luminance to 0.18)
  std::array<double, 3> Background{ 0.0, 0.0, 0.0 };   // sRGB in [0, 1]
  double StepSize = 0.0;                               // mm, longest march sub-step; 0: one voxel
  int SpecularSamples = 4;                             // per pixel axis, for the highlight
  int PixelSamples = 4;                                // per pixel axis, where an edge crosses a pixel
                                                       // (docs/design.md §3.4); 1: one ray per pixel
  int SpectralNodes = 16;                              // nodes of the body's scattering spectrum; 0: every
                                                       // wavelength (docs/design.md §3.4)
  bool LightFalloffAtEntry = false;                    // the paper's eq. 6: 1/r^2 stops at L_in
  // Beyond the paper (docs/design.md §7.2), off by default:
  BraggModelKind BraggModel = BraggModelKind::Paper;
  LatticePlaneSet LatticePlanes = LatticePlaneSet::Stacking111;
  int CoherentLayers = 200;                            // the most lattice layers reflecting coherently
  bool EnergyConservation = false;                     // 1 - R behind a crossing (always with coupled-wave)
  // The paper's here; VTK, ParaView and the CLI default to the volume's
  // (Volume: a custom volume's is all, docs/design.md §3.10).
  ScatteringOrdersKind ScatteringOrders = ScatteringOrdersKind::Single;
  int ScatteringPhotons = 1 << 14;                     // per spectral node of the every-order solve
  bool WriteSpectrum = false;                          // fill the Spectrum output
  RenderQuality Quality = RenderQuality::Final;
  int PreviewScale = 2;                                // a preview's pixels: 1/PreviewScale each way
  LightSpectrum Illuminant = LightSpectrum::D65;
};

// The largest number of wavelengths a render takes (the march keeps one
// radiance per wavelength in registers).
constexpr int MaxWavelengths = 401;

// The largest exposure, given or automatic: the colour pass multiplies in
// single precision, and beyond ~3.4e38 the product is infinite.
constexpr double MaxExposure = 1e30;

// One row per parameter of OPAL_RENDER_PARAMETERS, in its order
// (PresetRotation is the volume's, not a parameter a user sets).
const std::vector<ParameterRow<RenderParameters>>& renderParameterRows();

// Empty if valid, else one sentence naming the parameter: the rules between
// parameters and the open bounds first, then every row's range.
std::string validate(const RenderParameters& parameters);

// The parameters a frame renders with (Quality Final, the settings the
// quality implies): the same for Final; for Preview the image and its region
// divided by PreviewScale (sizes rounded up), WavelengthStep at least 20 nm, SpectralNodes 8 (0
// stays 0), SpecularSamples at most 2 and PixelSamples 1 (one ray per pixel).
RenderParameters withQuality(const RenderParameters& parameters);

// True if crossings keep 1 - R of the light: EnergyConservation, or the coupled-wave model.
bool conservesEnergy(const RenderParameters& parameters);

// True if the frame carries the light scattered more than once
// (docs/design.md §3.10). On resolved parameters: resolveFrame turns Volume
// into the volume's Single or All.
bool scattersEveryOrder(const RenderParameters& parameters);

// The lobe's angular deviation in degrees: MosaicSpread, or with the
// coupled-wave model CoupledWaveDefaultSpread where MosaicSpread is 0.
double effectiveMosaicSpread(const RenderParameters& parameters);

// Number of wavelength bins the parameters give.
int wavelengthCount(const RenderParameters& parameters);

} // namespace opal
