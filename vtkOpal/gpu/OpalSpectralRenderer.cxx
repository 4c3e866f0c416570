#include "OpalSpectralRenderer.h"

#include "OpalComputePipeline.h"
#include "OpalEmbeddedShaders.h"
#include "OpalMemory.h"
#include "OpalSpectralSampling.h"
#include "OpalVulkanBuffer.h"
#include "OpalVulkanError.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace opal
{

namespace
{
// Binding numbers of shaders/opal_render_layout.glsl and the passes.
enum Binding : std::uint32_t
{
  ParametersBinding = 0,
  WavelengthsBinding,
  ScatteringBinding,
  DomainIdBinding,
  SurfaceDistanceBinding,
  LightOpticalDepthBinding,
  LightGeometryBinding,
  DomainTableBinding,
  PixelXYZBinding,
  PixelBraggBinding,
  PixelSpectrumBinding,
  PixelRadianceBinding,
  PixelRGB8Binding,
  BindingCount
};
constexpr std::uint32_t PushConstantBytes = 16;
constexpr int MarchTile = 64;           // pixels per tile side: one submit each
constexpr int LightSlabVoxels = 1 << 18; // voxels per light-pass submit

// shaders/opal_render_layout.glsl RenderParameters (vec4s only: std140 = std430).
struct GpuParameters
{
  std::int32_t GridDims[4];
  float GridOrigin[4];
  float GridSpacing[4];
  float Eye[4];
  float Forward[4];
  float Right[4];
  float Up[4];
  float Light[4];
  std::int32_t Rect[4];
  float Optics[4];
  float Lighting[4];
  std::int32_t Counts[4];
  float Colour[4];
  float Background[4];
};
static_assert(sizeof(GpuParameters) == 14 * 16, "std430 layout of RenderParameters");

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void set4(float* to, const glm::dvec3& v, double w)
{
  to[0] = static_cast<float>(v.x);
  to[1] = static_cast<float>(v.y);
  to[2] = static_cast<float>(v.z);
  to[3] = static_cast<float>(w);
}

glm::dvec3 vec(const std::array<double, 3>& a)
{
  return { a[0], a[1], a[2] };
}

// Nearest-voxel SurfaceDistance at a model-frame point; +inf outside the grid.
double nearestSurfaceDistance(const RenderVolume& volume, const glm::dvec3& p)
{
  int c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = static_cast<int>(std::floor((p[a] - volume.Origin[a]) / volume.Spacing[a] + 0.5));
    if (c[a] < 0 || c[a] >= volume.Dimensions[a])
    {
      return INFINITY;
    }
  }
  const std::size_t index = static_cast<std::size_t>(c[0]) +
    static_cast<std::size_t>(volume.Dimensions[0]) *
      (static_cast<std::size_t>(c[1]) + static_cast<std::size_t>(volume.Dimensions[1]) * c[2]);
  return volume.SurfaceDistance[index];
}

// The opal's apex in the model frame: the top of the surface over the grid's
// centre column (SurfaceDistance crossing zero), or the top of the grid.
glm::dvec3 apexOf(const RenderVolume& volume)
{
  const int nx = volume.Dimensions[0], ny = volume.Dimensions[1], nz = volume.Dimensions[2];
  const int i = nx / 2, k = nz / 2;
  const double x = volume.Origin[0] + i * volume.Spacing[0];
  const double z = volume.Origin[2] + k * volume.Spacing[2];
  auto sd = [&](int j) {
    return volume.SurfaceDistance[static_cast<std::size_t>(i) +
      static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k)];
  };
  for (int j = ny - 1; j >= 0; --j)
  {
    if (sd(j) <= 0)
    {
      const double y0 = volume.Origin[1] + j * volume.Spacing[1];
      if (j + 1 < ny && sd(j + 1) > sd(j))
      {
        return { x, y0 + volume.Spacing[1] * (-sd(j)) / (sd(j + 1) - sd(j)), z };
      }
      return { x, y0 - sd(j), z };
    }
  }
  return { x, volume.Origin[1] + (ny - 0.5) * volume.Spacing[1], z };
}

// Whether the light sits above the grid steeply enough for the layer sweep:
// every path to it rises through each layer moving at most two voxels sideways.
bool lightAboveGrid(const RenderVolume& volume, const glm::dvec3& light)
{
  const glm::dvec3 spacing = vec(volume.Spacing);
  const glm::dvec3 low = vec(volume.Origin) - 0.5 * spacing;
  const glm::dvec3 high = low + glm::dvec3(volume.Dimensions[0], volume.Dimensions[1], volume.Dimensions[2]) * spacing;
  if (light.y < high.y + spacing.y)
  {
    return false;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y, (corner & 4) ? high.z : low.z);
    const glm::dvec3 d = light - p;
    if (std::fabs(d.x) / d.y * spacing.y > 2 * spacing.x || std::fabs(d.z) / d.y * spacing.y > 2 * spacing.z)
    {
      return false;
    }
  }
  return true;
}

void checkVolume(const RenderVolume& v)
{
  for (int a = 0; a < 3; ++a)
  {
    if (v.Dimensions[a] < 1 || !(v.Spacing[a] > 0))
    {
      throw std::invalid_argument("the input volume needs positive dimensions and spacing");
    }
  }
  if (!v.ScatteringCoefficient || !v.DomainId || !v.SurfaceDistance)
  {
    throw std::invalid_argument("the input volume lacks ScatteringCoefficient, DomainId or SurfaceDistance");
  }
}
} // namespace

SpectralRenderer::SpectralRenderer(const VulkanOptions& options)
  : Context(std::make_unique<VulkanContext>(options))
{
  std::vector<VkDescriptorType> types(BindingCount, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  types[ParametersBinding] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  this->Bindings = std::make_unique<StorageBufferBindings>(*this->Context, types, PushConstantBytes);
  const embedded::Spirv light = embedded::lightOpticalDepthShader();
  const embedded::Spirv colour = embedded::spectrumToColourShader();
  this->LightPass =
    std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, light.Words, light.WordCount);
  this->ColourPass =
    std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, colour.Words, colour.WordCount);
}

SpectralRenderer::~SpectralRenderer() = default;

RenderImage SpectralRenderer::render(
  const RenderVolume& volume, const RenderParameters& p, const std::function<bool(double)>& progress)
{
  const std::string error = validate(p);
  if (!error.empty())
  {
    throw std::invalid_argument(error);
  }
  checkVolume(volume);
  const auto setupStart = Clock::now();
  RenderImage image;

  // Camera and light in the model's frame: rotating the model by R is seeing
  // the unrotated model with everything else turned by R^-1.
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(p.ModelRotation[2]), glm::dvec3(0, 0, 1)) *
    glm::rotate(glm::dmat4(1.0), glm::radians(p.ModelRotation[1]), glm::dvec3(0, 1, 0)) *
    glm::rotate(glm::dmat4(1.0), glm::radians(p.ModelRotation[0]), glm::dvec3(1, 0, 0));
  const glm::dmat3 toModel = glm::transpose(glm::dmat3(rotation));
  const glm::dvec3 eye = toModel * vec(p.EyePosition);
  const glm::dvec3 light = toModel * vec(p.LightPosition);
  const glm::dvec3 forward = glm::normalize(toModel * (vec(p.FocalPoint) - vec(p.EyePosition)));
  glm::dvec3 right = glm::cross(forward, toModel * vec(p.ViewUp));
  if (glm::length(right) < 1e-9)
  {
    throw std::invalid_argument("ViewUp must not be parallel to the view direction.");
  }
  right = glm::normalize(right);
  const glm::dvec3 up = glm::cross(right, forward);
  if (nearestSurfaceDistance(volume, light) <= 0)
  {
    throw std::invalid_argument("LightPosition is inside the opal; place the light outside it.");
  }
  if (nearestSurfaceDistance(volume, eye) <= 0)
  {
    throw std::invalid_argument("EyePosition is inside the opal; place the eye outside it.");
  }

  const std::array<int, 4> region{ p.ImageRegion[0], p.ImageRegion[1],
    p.ImageRegion[2] > 0 ? p.ImageRegion[2] : p.ImageSize[0] - p.ImageRegion[0],
    p.ImageRegion[3] > 0 ? p.ImageRegion[3] : p.ImageSize[1] - p.ImageRegion[1] };
  const std::size_t pixels = static_cast<std::size_t>(region[2]) * region[3];
  // The automatic exposure's thumbnail of the whole image: at most 96 pixels across.
  const double thumbnailScale = std::min(1.0, 96.0 / std::max(p.ImageSize[0], p.ImageSize[1]));
  const std::array<int, 2> thumbnail{ std::max(1, static_cast<int>(std::lround(p.ImageSize[0] * thumbnailScale))),
    std::max(1, static_cast<int>(std::lround(p.ImageSize[1] * thumbnailScale))) };
  const std::size_t pixelCapacity = std::max(pixels, static_cast<std::size_t>(thumbnail[0]) * thumbnail[1]);
  const std::size_t voxels =
    static_cast<std::size_t>(volume.Dimensions[0]) * volume.Dimensions[1] * volume.Dimensions[2];
  const std::vector<WavelengthBin> bins = sampleWavelengths(p.WavelengthRange[0], p.WavelengthRange[1], p.WavelengthStep);
  const int wavelengths = static_cast<int>(bins.size());

  const double minSpacing = std::min({ volume.Spacing[0], volume.Spacing[1], volume.Spacing[2] });
  const double apexDistance2 = glm::dot(light - apexOf(volume), light - apexOf(volume));
  GpuParameters gpu{};
  gpu.GridDims[0] = volume.Dimensions[0];
  gpu.GridDims[1] = volume.Dimensions[1];
  gpu.GridDims[2] = volume.Dimensions[2];
  gpu.GridDims[3] = wavelengths;
  set4(gpu.GridOrigin, vec(volume.Origin), minSpacing);
  set4(gpu.GridSpacing, vec(volume.Spacing), p.StepSize > 0 ? p.StepSize : minSpacing);
  set4(gpu.Eye, eye, std::tan(glm::radians(p.ViewAngle) / 2));
  set4(gpu.Forward, forward, p.WriteSpectrum ? 1.0 : 0.0);
  set4(gpu.Right, right, p.ImageSize[0]);
  set4(gpu.Up, up, p.ImageSize[1]);
  set4(gpu.Light, light, p.LightRadius);
  std::copy(region.begin(), region.end(), gpu.Rect);
  gpu.Optics[0] = static_cast<float>(p.RefractiveIndex);
  gpu.Optics[1] = static_cast<float>(p.BraggBandwidth);
  gpu.Optics[2] = static_cast<float>(p.DiffractionGain);
  gpu.Optics[3] = static_cast<float>(glm::radians(p.MosaicSpread));
  // Irradiance 1 at the apex: intensity = apex distance^2; the light's
  // radiance spreads that intensity over its disc, pi r^2.
  gpu.Lighting[0] = static_cast<float>(apexDistance2);
  gpu.Lighting[1] = static_cast<float>(apexDistance2 / (3.14159265358979323846 * p.LightRadius * p.LightRadius));
  gpu.Lighting[2] = p.LightFalloffAtEntry ? 1.0f : 0.0f;
  gpu.Lighting[3] = static_cast<float>(p.SpecularSamples);
  gpu.Counts[0] = static_cast<std::int32_t>(volume.Domains.size());
  gpu.Counts[1] = p.BraggOrders;
  gpu.Colour[0] = 1.0f;
  set4(gpu.Background, vec(p.Background), 0.0);
  // Linear background for the Radiance array: the sRGB decoding of Background.
  for (int c = 0; c < 3; ++c)
  {
    const double b = p.Background[static_cast<std::size_t>(c)];
    gpu.Background[c] = static_cast<float>(b <= 0.04045 ? b / 12.92 : std::pow((b + 0.055) / 1.055, 2.4));
  }

  // Refuse up front what cannot fit, with the estimate: on the device, the
  // volume's fields and the light field (5 floats per voxel) and the images;
  // on the host, the output arrays.
  VulkanContext& context = *this->Context;
  const std::uint64_t spectrumBytes = p.WriteSpectrum ? static_cast<std::uint64_t>(pixels) * wavelengths * 4 : 0;
  const std::uint64_t deviceBytes = static_cast<std::uint64_t>(voxels) * 5 * 4 +
    static_cast<std::uint64_t>(pixelCapacity) * 4 * 4 * 3 + static_cast<std::uint64_t>(pixels) * 4 + spectrumBytes;
  if (deviceBytes > context.memoryBudget())
  {
    throw VulkanError("the render needs about " + formatBytes(deviceBytes) + " of device memory (volume " +
        formatBytes(static_cast<std::uint64_t>(voxels) * 20) + "), more than the device memory limit of " +
        formatBytes(context.memoryBudget()) + "; use fewer voxels or pixels",
      VK_ERROR_OUT_OF_DEVICE_MEMORY);
  }
  const std::uint64_t hostBytes = static_cast<std::uint64_t>(pixels) * (3 + 12 + 12 + 4 + 4 + 1) + spectrumBytes;
  if (physicalMemoryBytes() > 0 && hostBytes + deviceBytes > physicalMemoryBytes())
  {
    throw std::invalid_argument("ImageSize " + std::to_string(p.ImageSize[0]) + " x " +
      std::to_string(p.ImageSize[1]) + " needs about " + formatBytes(hostBytes + deviceBytes) +
      ", more than this machine's " + formatBytes(physicalMemoryBytes()) + " of memory.");
  }
  VulkanBuffer parameters(context, sizeof(GpuParameters), "render parameters");
  VulkanBuffer wavelengthTable(context, bins.size() * 8 * sizeof(float), "wavelength table");
  VulkanBuffer scattering(context, voxels * sizeof(float), "ScatteringCoefficient volume");
  VulkanBuffer domainIds(context, voxels * sizeof(std::int32_t), "DomainId volume");
  VulkanBuffer distance(context, voxels * sizeof(float), "SurfaceDistance volume");
  VulkanBuffer lightDepth(context, voxels * sizeof(float), "light optical depth volume");
  VulkanBuffer lightGeometry(context, voxels * sizeof(float), "light geometry volume");
  VulkanBuffer domainTable(context, volume.Domains.size() * 4 * sizeof(float), "domain table");
  VulkanBuffer pixelXYZ(context, pixelCapacity * 4 * sizeof(float), "XYZ image");
  VulkanBuffer pixelBragg(context, pixelCapacity * 4 * sizeof(float), "Bragg image");
  VulkanBuffer pixelSpectrum(context, p.WriteSpectrum ? pixels * wavelengths * sizeof(float) : 16, "Spectrum image");
  VulkanBuffer pixelRadiance(context, pixels * 4 * sizeof(float), "Radiance image");
  VulkanBuffer pixelRGB8(context, pixels * sizeof(std::uint32_t), "RGB image");
  this->Bindings->bind({ &parameters, &wavelengthTable, &scattering, &domainIds, &distance, &lightDepth,
    &lightGeometry, &domainTable, &pixelXYZ, &pixelBragg, &pixelSpectrum, &pixelRadiance, &pixelRGB8 });
  std::unique_ptr<ComputePipeline>& march = this->MarchPasses[wavelengths];
  if (!march)
  {
    const embedded::Spirv code = embedded::viewMarchShader();
    march = std::make_unique<ComputePipeline>(context, *this->Bindings, code.Words, code.WordCount,
      std::vector<std::int32_t>{ wavelengths });
  }
  image.Timings.Setup = secondsSince(setupStart);

  const auto uploadStart = Clock::now();
  parameters.upload(&gpu, sizeof(gpu));
  float* table = wavelengthTable.as<float>();
  for (const WavelengthBin& bin : bins)
  {
    const float entries[8] = { static_cast<float>(bin.Lambda), static_cast<float>(bin.RayleighScale),
      static_cast<float>(bin.D65), static_cast<float>(bin.Width), static_cast<float>(bin.XBar),
      static_cast<float>(bin.YBar), static_cast<float>(bin.ZBar), 0.0f };
    std::copy(entries, entries + 8, table);
    table += 8;
    image.Wavelengths.push_back(bin.Lambda);
  }
  scattering.upload(volume.ScatteringCoefficient, voxels * sizeof(float));
  domainIds.upload(volume.DomainId, voxels * sizeof(std::int32_t));
  distance.upload(volume.SurfaceDistance, voxels * sizeof(float));
  if (!volume.Domains.empty())
  {
    domainTable.upload(volume.Domains.data(), volume.Domains.size() * 4 * sizeof(float));
  }
  image.Timings.Upload = secondsSince(uploadStart);

  // Progress: light pass 20%, march 75%, colour 5%.
  auto report = [&](double fraction) { return !progress || progress(fraction); };

  const auto lightStart = Clock::now();
  if (lightAboveGrid(volume, light))
  {
    // Sweep layer by layer from the top: each layer reads the one above.
    const int layers = volume.Dimensions[1];
    const std::uint32_t groups =
      static_cast<std::uint32_t>((volume.Dimensions[0] * volume.Dimensions[2] + 255) / 256);
    constexpr int LayersPerSubmit = 16;
    for (int top = layers - 1; top >= 0; top -= LayersPerSubmit)
    {
      context.submitAndWait([&](VkCommandBuffer commands) {
        for (int layer = top; layer > top - LayersPerSubmit && layer >= 0; --layer)
        {
          const std::int32_t work[4] = { 1, 0, 0, layer };
          this->LightPass->dispatch(commands, work, groups);
        }
      });
      if (!report(0.2 * static_cast<double>(layers - std::max(0, top - LayersPerSubmit + 1)) / layers))
      {
        return RenderImage{};
      }
    }
  }
  else
  {
    for (std::size_t first = 0; first < voxels; first += LightSlabVoxels)
    {
      const std::int32_t count = static_cast<std::int32_t>(std::min<std::size_t>(LightSlabVoxels, voxels - first));
      const std::int32_t work[4] = { 0, static_cast<std::int32_t>(first), count, 0 };
      context.submitAndWait([&](VkCommandBuffer commands) {
        this->LightPass->dispatch(commands, work, static_cast<std::uint32_t>((count + 255) / 256));
      });
      if (!report(0.2 * static_cast<double>(first + static_cast<std::size_t>(count)) / voxels))
      {
        return RenderImage{};
      }
    }
  }
  image.Timings.LightPass = secondsSince(lightStart);

  // March a rectangle of an image of the given size, in tiles (one submit
  // each, so no frame trips a device timeout), reporting progress in [from, to].
  GpuParameters* block = parameters.as<GpuParameters>();
  auto marchRegion = [&](const std::array<int, 2>& size, const std::array<int, 4>& rect, bool spectrum,
                       double from, double to) {
    block->Right[3] = static_cast<float>(size[0]);
    block->Up[3] = static_cast<float>(size[1]);
    std::copy(rect.begin(), rect.end(), block->Rect);
    block->Forward[3] = spectrum ? 1.0f : 0.0f;
    const int tilesX = (rect[2] + MarchTile - 1) / MarchTile;
    const int tilesY = (rect[3] + MarchTile - 1) / MarchTile;
    for (int ty = 0; ty < tilesY; ++ty)
    {
      for (int tx = 0; tx < tilesX; ++tx)
      {
        const std::int32_t origin[4] = { tx * MarchTile, ty * MarchTile, 0, 0 };
        context.submitAndWait([&](VkCommandBuffer commands) {
          march->dispatch(commands, origin, MarchTile / 8, MarchTile / 8);
        });
        if (!report(from + (to - from) * static_cast<double>(ty * tilesX + tx + 1) / (tilesX * tilesY)))
        {
          return false;
        }
      }
    }
    return true;
  };

  // Automatic exposure: the body's median luminance to a mid grey (0.18),
  // measured on a thumbnail of the whole image, so that any region or piece
  // of the image gets the same exposure and pieces agree with the whole.
  const auto marchStart = Clock::now();
  const float* xyz = pixelXYZ.as<float>();
  const float* bragg = pixelBragg.as<float>();
  double exposure = p.Exposure;
  if (exposure <= 0)
  {
    if (!marchRegion(thumbnail, { 0, 0, thumbnail[0], thumbnail[1] }, false, 0.2, 0.25))
    {
      return RenderImage{};
    }
    std::vector<float> luminance;
    for (std::size_t i = 0; i < static_cast<std::size_t>(thumbnail[0]) * thumbnail[1]; ++i)
    {
      if (bragg[4 * i + 2] > 0.5f && xyz[4 * i + 1] > 0)
      {
        luminance.push_back(xyz[4 * i + 1]);
      }
    }
    exposure = 1.0;
    if (!luminance.empty())
    {
      std::nth_element(luminance.begin(), luminance.begin() + luminance.size() / 2, luminance.end());
      exposure = 0.18 / luminance[luminance.size() / 2];
    }
  }
  if (!marchRegion(p.ImageSize, region, p.WriteSpectrum, 0.25, 0.95))
  {
    return RenderImage{};
  }
  image.Timings.March = secondsSince(marchStart);

  const auto colourStart = Clock::now();
  image.Exposure = exposure;
  block->Colour[0] = static_cast<float>(exposure);
  constexpr std::size_t ColourChunk = 65535 * 64;
  for (std::size_t first = 0; first < pixels; first += ColourChunk)
  {
    const std::int32_t range[4] = { static_cast<std::int32_t>(first), 0, 0, 0 };
    const std::size_t count = std::min(ColourChunk, pixels - first);
    context.submitAndWait([&](VkCommandBuffer commands) {
      this->ColourPass->dispatch(commands, range, static_cast<std::uint32_t>((count + 63) / 64));
    });
  }
  image.Timings.Colour = secondsSince(colourStart);

  const auto readStart = Clock::now();
  image.ImageSize = p.ImageSize;
  image.Region = region;
  image.RGB.resize(pixels * 3);
  image.Radiance.resize(pixels * 3);
  image.XYZ.resize(pixels * 3);
  image.DominantBraggWavelength.resize(pixels);
  image.Depth.resize(pixels);
  image.Hit.resize(pixels);
  const std::uint32_t* rgb8 = pixelRGB8.as<std::uint32_t>();
  const float* radiance = pixelRadiance.as<float>();
  for (std::size_t i = 0; i < pixels; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      image.RGB[3 * i + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>((rgb8[i] >> (8 * c)) & 0xffu);
      image.Radiance[3 * i + static_cast<std::size_t>(c)] = radiance[4 * i + static_cast<std::size_t>(c)];
      image.XYZ[3 * i + static_cast<std::size_t>(c)] = xyz[4 * i + static_cast<std::size_t>(c)];
    }
    image.Depth[i] = xyz[4 * i + 3];
    image.DominantBraggWavelength[i] = bragg[4 * i];
    image.Hit[i] = bragg[4 * i + 2] > 0.5f ? 1 : 0;
  }
  if (p.WriteSpectrum)
  {
    const float* spectrum = pixelSpectrum.as<float>();
    image.Spectrum.assign(spectrum, spectrum + pixels * static_cast<std::size_t>(wavelengths));
  }
  image.Timings.Readback = secondsSince(readStart);
  report(1.0);
  return image;
}

} // namespace opal
