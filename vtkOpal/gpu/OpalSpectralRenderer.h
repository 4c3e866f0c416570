// The spectral render of the opal volume on Vulkan compute (DESIGN.md §3):
// LightOpticalDepthPass, ViewMarchPass (tiled), SpectrumToColourPass.
// Plain C++: the VTK filter and the command-line renderer wrap it.
#pragma once

#include "OpalRenderParameters.h"
#include "OpalVulkanContext.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace opal
{

class ComputePipeline;
class StorageBufferBindings;

// The voxel fields the render reads (DESIGN.md §2 arrays), x fastest.
struct RenderVolume
{
  std::array<int, 3> Dimensions{};
  std::array<double, 3> Origin{};  // centre of voxel (0, 0, 0), mm
  std::array<double, 3> Spacing{}; // mm
  const float* ScatteringCoefficient = nullptr; // 1/mm at 550 nm
  const std::int32_t* DomainId = nullptr;       // -1 or index into Domains
  const float* SurfaceDistance = nullptr;       // mm, negative inside
  // Per domain: lattice-plane normal (x, y, z) and FCC (111) plane spacing d in nm.
  std::vector<std::array<float, 4>> Domains;
};

struct RenderTimings
{
  double Setup = 0;    // device buffers, pipelines
  double Upload = 0;   // volume into device buffers
  double LightPass = 0;
  double March = 0;
  double Colour = 0;
  double Readback = 0;
};

// The rendered rectangle, rows top to bottom.
struct RenderImage
{
  std::array<int, 2> ImageSize{};
  std::array<int, 4> Region{};                 // x0, y0, width, height
  std::vector<std::uint8_t> RGB;               // 3 per pixel, sRGB
  std::vector<float> Radiance;                 // 3 per pixel, linear sRGB
  std::vector<float> XYZ;                      // 3 per pixel
  std::vector<float> DominantBraggWavelength;  // nm, 0 where no domain diffracts
  std::vector<float> Depth;                    // mm from the eye to the surface, 0 where missed
  std::vector<std::uint8_t> Hit;               // 1 where the ray meets the opal
  std::vector<float> Spectrum;                 // Wavelengths.size() per pixel, if asked for
  std::vector<double> Wavelengths;             // nm
  double Exposure = 1;
  RenderTimings Timings;
};

class SpectralRenderer
{
public:
  // Creates the Vulkan context (throws NoVulkanDeviceError / VulkanError).
  explicit SpectralRenderer(const VulkanOptions& options = {});
  ~SpectralRenderer();

  // Renders; progress(fraction) may return false to abort (then returns an
  // empty image with ImageSize 0). Throws std::invalid_argument for bad
  // parameters (naming the parameter) and VulkanError for device failures.
  RenderImage render(const RenderVolume& volume, const RenderParameters& parameters,
    const std::function<bool(double)>& progress = nullptr);

  VulkanContext& context() { return *this->Context; }

private:
  std::unique_ptr<VulkanContext> Context;
  std::unique_ptr<StorageBufferBindings> Bindings;
  std::unique_ptr<ComputePipeline> LightPass;
  std::unique_ptr<ComputePipeline> ColourPass;
  std::map<int, std::unique_ptr<ComputePipeline>> MarchPasses; // by wavelength count
};

} // namespace opal
