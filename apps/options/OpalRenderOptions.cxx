#include "OpalRenderOptions.h"

#include "OpalCliArrays.h"
#include "OpalPresets.h"

#include <cmath>
#include <cstdlib>

void OpalRenderOptions::addTo(CLI::App& app)
{
  opal::RenderParameters& p = this->Parameters;
  const std::string group = "Render";
  this->WidthOption = app.add_option("--width", p.ImageSize[0], "Image width in pixels (default: the preset's)")->group(group);
  this->HeightOption = app.add_option("--height", p.ImageSize[1], "Image height in pixels (default: the preset's)")->group(group);
  addArrayOption(app, "--image-region", p.ImageRegion,
    "Render only X0 Y0 WIDTH HEIGHT of the image (from the top left; <= 0 reaches the edge)", group);
  addArrayOption(app, "--eye-position", p.EyePosition, "Eye position in mm (0 60 0)", group);
  addArrayOption(app, "--focal-point", p.FocalPoint, "Point looked at in mm (0 0 0)", group);
  addArrayOption(app, "--view-up", p.ViewUp, "Image up direction (0 0 -1)", group);
  app.add_option("--view-angle", p.ViewAngle, "Vertical view angle in degrees")->capture_default_str()->group(group);
  addArrayOption(app, "--light-position", p.LightPosition, "D65 point light position in mm (0 60 0)", group);
  app.add_option("--light-radius", p.LightRadius, "Radius of the light's sphere in mm")->capture_default_str()->group(group);
  // ModelRotation's first component by another name: checked here, so a refusal names the flag given.
  app.add_option("--rotate-x", p.ModelRotation[0], "Turn the stone about x by degrees, after the preset's placement (fig13: 5)")
    ->check(CLI::Validator(
      [](std::string& value) {
        const double number = std::strtod(value.c_str(), nullptr); // a non-number is CLI11's to refuse
        return std::isfinite(number) ? std::string() : std::string("must be finite");
      },
      "DEGREES"))
    ->group(group);
  addArrayOption(app, "--model-rotation", p.ModelRotation, "Turn the stone about x, y, z by degrees, after the preset's placement", group);
  addArrayOption(app, "--wavelength-range", p.WavelengthRange, "Wavelengths MIN MAX in nm (380 780)", group);
  app.add_option("--wavelength-step", p.WavelengthStep, "Wavelength step in nm")->capture_default_str()->group(group);
  app.add_option("--bragg-bandwidth", p.BraggBandwidth, "Relative full width of the Bragg band")
    ->capture_default_str()
    ->group(group);
  app.add_option("--diffraction-gain", p.DiffractionGain, "Diffraction gain G (paper: 4)")
    ->capture_default_str()
    ->group(group);
  app.add_option("--bragg-orders", p.BraggOrders, "Bragg orders k = 1..N")->capture_default_str()->group(group);
  app.add_option("--mosaic-spread", p.MosaicSpread, "Angular gating of diffraction in degrees (0 = off, the paper)")
    ->capture_default_str()
    ->group(group);
  app.add_option("--exposure", p.Exposure, "Exposure multiplier (0 = automatic)")->capture_default_str()->group(group);
  addArrayOption(app, "--background", p.Background, "Background colour, sRGB R G B in [0, 1]", group);
  app.add_option("--step-size", p.StepSize, "Longest march sub-step in mm (0 = one voxel)")
    ->capture_default_str()
    ->group(group);
  app.add_option("--spectral-nodes", p.SpectralNodes,
       "Nodes of the body's scattering spectrum (0: evaluate every wavelength)")
    ->capture_default_str()
    ->group(group);
  addEnumOption(app, "--illuminant", p.Illuminant,
    { { "D65", opal::LightSpectrum::D65 }, { "none", opal::LightSpectrum::None } },
    "The light's spectrum: D65 (normalised to luminance 1), or none (unit spectral irradiance)", group);
  addEnumOption(app, "--quality", p.Quality,
    { { "final", opal::RenderQuality::Final }, { "preview", opal::RenderQuality::Preview } },
    "final, or preview: half the width and height, 20 nm steps, 8 spectral nodes, a 2 x 2 highlight, twice the march step, the light read per voxel", group);
  app.add_option("--specular-samples", p.SpecularSamples, "Sub-rays per pixel axis for the highlight")
    ->capture_default_str()
    ->group(group);
  app.add_flag("--light-falloff-at-entry", p.LightFalloffAtEntry,
       "The paper's eq. 6: stop the 1/r^2 fall-off at the light's entry point")
    ->group(group);
  this->addBraggModelOptions(app);
  app.add_option("--device", this->DeviceIndex, "Vulkan device index (-1: OPAL_VULKAN_DEVICE or the best)")
    ->capture_default_str()
    ->group(group);
  app.add_option("--device-memory-limit", this->DeviceMemoryLimit, "Refuse device memory beyond this many MB (0: none)")
    ->capture_default_str()
    ->group(group);
}

// The coupled-wave Bragg model and the lattice planes (docs/design.md §7.2).
void OpalRenderOptions::addBraggModelOptions(CLI::App& app)
{
  opal::RenderParameters& p = this->Parameters;
  const std::string group = "Render";
  this->BraggModelOption = addEnumOption(app, "--bragg-model", p.BraggModel,
    { { "paper", opal::BraggModelKind::Paper }, { "coupled-wave", opal::BraggModelKind::CoupledWave } },
    "paper (the box band of gain G) or coupled-wave (the reflectance of the lattice layers into a lobe)", group);
  this->LatticePlanesOption = addEnumOption(app, "--lattice-planes", p.LatticePlanes,
    { { "111", opal::LatticePlaneSet::Stacking111 }, { "fcc", opal::LatticePlaneSet::Fcc } },
    "111 (the stacking planes, the paper) or fcc (all 13 families; needs --bragg-model coupled-wave)", group);
  app.add_option("--coherent-layers", p.CoherentLayers, "The most lattice layers that reflect coherently")
    ->capture_default_str()
    ->group(group);
  app.add_flag("--energy-conservation", p.EnergyConservation,
       "Light behind a domain keeps 1 - R of what it reflects (always with coupled-wave)")
    ->group(group);
}

opal::RenderParameters OpalRenderOptions::parameters(const std::string& presetName, double refractiveIndex) const
{
  opal::RenderParameters p = this->Parameters;
  if (const opal::PresetSettings* preset = opal::presetByIndex(opal::presetIndexByName(presetName)))
  {
    if (this->WidthOption->count() == 0)
    {
      p.ImageSize[0] = preset->ImageSize[0];
    }
    if (this->HeightOption->count() == 0)
    {
      p.ImageSize[1] = preset->ImageSize[1];
    }
    p.PresetRotation = { preset->RotateXDegrees, 0.0, 0.0 };
    // The kinds of opal set the Bragg model and planes (docs/design.md §2.11).
    if (this->BraggModelOption->count() == 0)
    {
      p.BraggModel = preset->BraggModel;
    }
    if (this->LatticePlanesOption->count() == 0)
    {
      p.LatticePlanes = preset->LatticePlanes;
    }
  }
  p.RefractiveIndex = refractiveIndex;
  return p;
}
