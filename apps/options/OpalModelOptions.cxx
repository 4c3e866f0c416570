#include "OpalModelOptions.h"

#include "OpalCliArrays.h"

#include "OpalPresets.h"



void OpalModelOptions::addTo(CLI::App& app)
{
  opal::ModelParameters& p = this->Parameters;
  app.add_option("--preset", this->Preset, "The paper's figure to reproduce: " + opal::presetNameList())
    ->check(CLI::IsMember({ "custom", "fig10", "fig11", "fig12", "fig13", "fig15", "fig17" }))
    ->capture_default_str()
    ->group("Model");
  addArrayOption(app, "--dimensions", p.Dimensions, "Voxels along x y z (160 80 200)", "Model");
  addArrayOption(app, "--physical-size", p.PhysicalSize, "Box size in mm along x y z (16 8 20)", "Model");
  addArrayOption(app, "--semi-axes", p.SemiAxes, "Half-ellipsoid semi-axes a b c in mm (8 8 10)", "Model");
  addArrayOption(app, "--scattering-diameter-range", p.ScatteringDiameterRange,
    "Scattering sphere diameters MIN MAX in nm (5 50)", "Model");
  app.add_option("--scattering-volume-fraction", p.ScatteringVolumeFraction,
       "Silica volume fraction of the milky body, (0, 0.74]")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--domain-count", p.DomainCount, "Diffraction domains to place")
    ->capture_default_str()
    ->group("Model");
  addArrayOption(app, "--domain-vertex-range", p.DomainVertexRange, "Polygon vertex count MIN MAX (5 8)", "Model");
  addArrayOption(
    app, "--domain-radius-range", p.DomainRadiusRange, "Polygon circumradius MIN MAX in mm (0.5 1.5)", "Model");
  addArrayOption(app, "--domain-vertex-jitter", p.DomainVertexJitter,
    "Vertex position on its spoke MIN MAX, fraction of the radius (0.4 1)", "Model");
  addArrayOption(
    app, "--domain-angle-range", p.DomainAngleRange, "Allowed interior angles MIN MAX in degrees (30 170)", "Model");
  addArrayOption(app, "--domain-rotation-range", p.DomainRotationRange,
    "Tilt of the domain normal from +y MIN MAX in degrees (0 30)", "Model");
  this->DomainDiameterRangeOption = addArrayOption(app, "--domain-diameter-range",
    p.DomainDiameterRange, "Domain sphere diameters MIN MAX in nm (default: the preset's)", "Model");
  app.add_option("--refractive-index", p.RefractiveIndex, "Refractive index of opal")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--max-placement-attempts", p.MaxPlacementAttempts, "Attempts per domain")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--seed", p.Seed, "Seed of every random choice of the model")
    ->capture_default_str()
    ->group("Model");
}

opal::ModelParameters OpalModelOptions::parameters() const
{
  opal::ModelParameters resolved = this->Parameters;
  resolved.applyPreset(this->presetIndex());
  return resolved;
}

int OpalModelOptions::presetIndex() const
{
  // An explicit --domain-diameter-range wins over the preset's.
  const bool ownDiameters = this->DomainDiameterRangeOption && this->DomainDiameterRangeOption->count() > 0;
  return ownDiameters ? opal::CustomPreset : opal::presetIndexByName(this->Preset);
}
