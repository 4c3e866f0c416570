// Synthetic scenes for the render tests: a box-shaped opal (a slab) with a
// uniform scattering coefficient and at most one flat domain, rendered from
// above with the paper's set-up (light at the eye). Plain C++ around
// opal::RenderSession, plus helpers to skip without a Vulkan device.
#pragma once

#include "OpalDomainLayout.h"
#include "OpalGrid.h"
#include "OpalLatticePlanes.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderSession.h"
#include "OpalVulkanError.h"

#include "vtkTesting.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <stdexcept>
#include <vector>

namespace opaltest
{

// What a Vulkan test returns without a Vulkan device: VTK's skip code
// (vtk_add_test_cxx tells ctest), except in CI (CI=true), where lavapipe is
// installed and every Vulkan test must run: there it fails.
inline int noDeviceReturnCode()
{
  const char* ci = std::getenv("CI");
  if (ci && std::string(ci) == "true")
  {
    std::cout << "FAILED: no Vulkan device in CI (CI=true), where every Vulkan test must run" << std::endl;
    return EXIT_FAILURE;
  }
  return VTK_SKIP_RETURN_CODE;
}

// Whether this machine has a Vulkan device; says why not if it has none.
// Every Vulkan test asks first, so this also turns the validation layer on
// for each render of the test process (OPAL_VULKAN_VALIDATION): the tests'
// checks that it stayed silent hold however the test is run, not only under
// ctest's environment.
inline bool vulkanDeviceAvailable()
{
  setenv("OPAL_VULKAN_VALIDATION", "1", 1);
  try
  {
    opal::VulkanContext probe;
    return true;
  }
  catch (const opal::NoVulkanDeviceError& e)
  {
    std::cout << "No Vulkan device: " << e.what() << std::endl;
    return false;
  }
}

// A render session that renders a scene per call: its volume, then a frame
// that must complete.
class SceneRenderer
{
public:
  explicit SceneRenderer(const opal::VulkanOptions& options) : Session(options) {}

  opal::RenderImage render(const opal::RenderVolume& volume, const opal::RenderParameters& parameters)
  {
    this->Session.setVolume(volume);
    opal::RenderFrame frame = this->Session.render(parameters);
    if (frame.Status != opal::FrameStatus::Completed)
    {
      throw std::runtime_error("the frame did not complete");
    }
    // Every test's frames under the validation layer (synchronization included): any message fails it.
    const std::vector<std::string> messages = this->Session.context().validationMessages();
    if (!messages.empty())
    {
      throw std::runtime_error("the Vulkan validation layer reported: " + messages.front());
    }
    return std::move(frame.Image);
  }

  opal::VulkanContext& context() { return this->Session.context(); }

  opal::RenderSession Session;
};

// Two renders of the same frame equal value for value: every image array,
// the spectrum where kept, and the exposure.
inline bool identical(const opal::RenderImage& a, const opal::RenderImage& b)
{
  return a.RGB == b.RGB && a.XYZ == b.XYZ && a.Radiance == b.Radiance && a.Spectrum == b.Spectrum &&
    a.DominantBraggWavelength == b.DominantBraggWavelength && a.Depth == b.Depth && a.Exposure == b.Exposure;
}

// `p` with the Bragg model and lattice planes preset `preset` (of refractive
// index `refractiveIndex`) renders with, as the VTK filter takes them.
inline opal::RenderParameters withPresetHints(opal::RenderParameters p, const char* preset, double refractiveIndex)
{
  const opal::VolumeRenderHints hints = opal::renderHints(opal::presetIndexByName(preset), refractiveIndex);
  p.BraggModel = hints.BraggModel.value_or(p.BraggModel);
  p.LatticePlanes = hints.LatticePlanes.value_or(p.LatticePlanes);
  return p;
}

// The renderer with the validation layer on, or nullptr (and a message) if
// this machine has no Vulkan device.
inline std::unique_ptr<SceneRenderer> makeRenderer()
{
  try
  {
    opal::VulkanOptions options;
    options.Validation = true;
    return std::make_unique<SceneRenderer>(options);
  }
  catch (const opal::NoVulkanDeviceError& e)
  {
    std::cout << "No Vulkan device: " << e.what() << std::endl;
    return nullptr;
  }
}

struct SlabScene
{
  // An 8 x 2 x 8 mm slab of 80 x 20 x 80 voxels, top face at y = 2.
  std::array<int, 3> Dimensions{ 80, 20, 80 };
  double Spacing = 0.1;
  double Scattering = 0.0;                 // mu_s(550) in 1/mm everywhere inside
  double Absorption = 0.0;                 // mu_a(550) in 1/mm everywhere, domain included (0: no arrays)
  double AbsorptionExponent = 0.0;         // p of mu_a(lambda) = mu_a(550) (550/lambda)^p
  bool WithDomain = false;
  glm::dvec3 DomainCentre{ 0.0, 1.0, 0.0 };
  glm::dvec3 DomainNormal{ 0.0, 1.0, 0.0 };
  double DomainHalfSize = 2.5;             // mm, a square
  double PlaneSpacing = 200.0;             // nm, FCC (111) d
  double DomainSpin = 0.0;                 // radians: the lattice's turn about DomainNormal
  std::vector<glm::dvec3> MoreDomainCentres; // copies of the domain centred there (ids 1, 2, ...)

  std::vector<float> ScatteringField, DistanceField, AbsorptionField, ExponentField;
  std::vector<std::int32_t> DomainField;
  std::vector<std::array<int, 3>> DomainVoxels;
  opal::Grid VoxelGrid;

  // The square domain (DomainNormal, DomainHalfSize, PlaneSpacing, DomainSpin) at `centre`, id `id`.
  void addDomain(opal::RenderVolume& volume, const glm::dvec3& centre, std::int32_t id)
  {
    const glm::dvec3 n = glm::normalize(this->DomainNormal);
    const glm::dvec3 helper = std::fabs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(n, helper));
    const glm::dvec3 v = glm::cross(n, u);
    std::vector<std::array<double, 3>> square;
    for (const auto& corner : { glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1) })
    {
      const glm::dvec3 q = centre + this->DomainHalfSize * (corner.x * u + corner.y * v);
      square.push_back({ q.x, q.y, q.z });
    }
    std::vector<std::array<int, 3>> voxels;
    opal::rasterisePolygon(this->VoxelGrid, square, { n.x, n.y, n.z }, voxels);
    for (const auto& c : voxels)
    {
      const auto index = static_cast<std::size_t>(this->VoxelGrid.linearIndex(c[0], c[1], c[2]));
      this->DomainField[index] = id;
      this->ScatteringField[index] = 0.0f; // no scattering in domains (paper §6.2)
    }
    this->DomainVoxels.insert(this->DomainVoxels.end(), voxels.begin(), voxels.end());
    const glm::dquat q = opal::latticeOrientation(n, this->DomainSpin);
    volume.Domains.push_back({ { static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z) },
      static_cast<float>(this->PlaneSpacing),
      { static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z) } });
  }

  opal::RenderVolume build()
  {
    opal::ModelParameters p;
    p.Dimensions = this->Dimensions;
    p.PhysicalSize = { this->Dimensions[0] * this->Spacing, this->Dimensions[1] * this->Spacing,
      this->Dimensions[2] * this->Spacing };
    this->VoxelGrid = opal::Grid::fromParameters(p);
    const std::size_t count = static_cast<std::size_t>(this->VoxelGrid.voxelCount());
    this->ScatteringField.assign(count, static_cast<float>(this->Scattering));
    this->DomainField.assign(count, -1);
    this->DistanceField.resize(count);
    const double halfX = p.PhysicalSize[0] / 2, top = p.PhysicalSize[1], halfZ = p.PhysicalSize[2] / 2;
    for (int k = 0; k < this->Dimensions[2]; ++k)
      for (int j = 0; j < this->Dimensions[1]; ++j)
        for (int i = 0; i < this->Dimensions[0]; ++i)
        {
          const auto x = this->VoxelGrid.position(i, j, k);
          // Inside a box the signed distance is the largest of the face distances.
          const double d = std::max({ std::fabs(x[0]) - halfX, x[1] - top, -x[1], std::fabs(x[2]) - halfZ });
          this->DistanceField[static_cast<std::size_t>(this->VoxelGrid.linearIndex(i, j, k))] = static_cast<float>(d);
        }
    opal::RenderVolume volume;
    volume.Dimensions = this->Dimensions;
    volume.Origin = this->VoxelGrid.Origin;
    volume.Spacing = this->VoxelGrid.Spacing;
    if (this->WithDomain)
    {
      this->DomainVoxels.clear();
      std::vector<glm::dvec3> centres{ this->DomainCentre };
      centres.insert(centres.end(), this->MoreDomainCentres.begin(), this->MoreDomainCentres.end());
      for (std::size_t id = 0; id < centres.size(); ++id)
      {
        this->addDomain(volume, centres[id], static_cast<std::int32_t>(id));
      }
    }
    volume.ScatteringCoefficient = this->ScatteringField.data();
    volume.DomainId = this->DomainField.data();
    volume.SurfaceDistance = this->DistanceField.data();
    if (this->Absorption > 0)
    {
      this->AbsorptionField.assign(count, static_cast<float>(this->Absorption));
      this->ExponentField.assign(count, static_cast<float>(this->AbsorptionExponent));
      volume.AbsorptionCoefficient = this->AbsorptionField.data();
      volume.AbsorptionExponent = this->ExponentField.data();
    }
    return volume;
  }
};

// The paper's set-up over the slab: light at the eye 28 mm above its top.
inline opal::RenderParameters slabView(int size = 33)
{
  opal::RenderParameters p;
  p.ImageSize = { size, size };
  p.EyePosition = { 0.0, 30.0, 0.0 };
  p.LightPosition = { 0.0, 30.0, 0.0 };
  p.ViewAngle = 12.0;
  p.Exposure = 1.0;
  return p;
}

inline bool allFinite(const opal::RenderImage& image)
{
  auto finite = [](const std::vector<float>& values) {
    return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
  };
  return finite(image.Radiance) && finite(image.XYZ) && finite(image.DominantBraggWavelength) &&
    finite(image.Depth) && finite(image.Spectrum);
}

inline std::size_t pixelIndex(const opal::RenderImage& image, int x, int y)
{
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(image.Region[2]) + static_cast<std::size_t>(x);
}

} // namespace opaltest
