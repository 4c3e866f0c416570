// What a render produces: the rendered rectangle of the image, rows top to
// bottom, with every output array (docs/design.md §6). Plain data.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace opal
{

// Seconds spent in each stage of the frame (0 for a stage that did not run).
struct RenderTimings
{
  double Setup = 0;    // frame set-up, buffers, pipelines
  double Upload = 0;   // the volume into device buffers
  double LightPass = 0;
  double ScatteredLight = 0; // the every-order solve (docs/design.md §3.10)
  double March = 0;    // the exposure thumbnail and the image
  // Of March, in a march shared by processes (docs/design.md §8.1): its
  // rounds' exchanges, waits for the other shares included, and the ray
  // states' copies between the host and the device.
  double MarchRounds = 0;
  double Colour = 0;
  double Readback = 0;
};

struct RenderImage
{
  std::array<int, 2> ImageSize{};
  std::array<int, 4> Region{};                 // x0, y0, width, height
  std::vector<std::uint8_t> RGB;               // 3 per pixel, sRGB
  std::vector<float> Radiance;                 // 3 per pixel, linear sRGB
  std::vector<float> XYZ;                      // 3 per pixel
  std::vector<float> DominantBraggWavelength;  // nm, 0 where no domain diffracts
  std::vector<float> Depth;                    // mm from the eye to the surface, 0 where missed
  std::vector<float> Spectrum;                 // Wavelengths.size() per pixel, if asked for
  std::vector<double> Wavelengths;             // nm
  double Exposure = 1;
  // The light's spectrum: "D65" (normalised by IlluminantScale, luminance 1)
  // or "none" (unit spectral irradiance, IlluminantScale 1).
  std::string Illuminant = "D65";
  double IlluminantScale = 1;
  std::string ScatteringOrders = "single"; // "single" or "all", as rendered
  // Empty, or what the frame could not do fully (the every-order solve's budget).
  std::string Warning;
  RenderTimings Timings;
  // The most device memory the render session's buffers held at once, up to
  // this frame (bytes; on a CPU driver, host memory).
  std::uint64_t DeviceMemoryPeak = 0;
};

// The first output array holding a NaN or an infinity, by name; empty if
// every value is finite. A render must never hand such an image on.
std::string nonFiniteArray(const RenderImage& image);

} // namespace opal
