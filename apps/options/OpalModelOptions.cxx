#include "OpalModelOptions.h"

#include "OpalCliArrays.h"

#include "OpalModelFields.h"
#include "OpalPresets.h"

void OpalModelOptions::addTo(CLI::App& app)
{
  opal::ModelParameters& p = this->Parameters;
  std::vector<std::string> presetNames{ "custom" };
  for (const opal::PresetSettings& preset : opal::presets())
  {
    presetNames.emplace_back(preset.Name);
  }
  app.add_option("--preset", this->Preset,
       "The paper's figure to reproduce, or a Voronoi opal (harlequin, pinfire): " + opal::presetNameList())
    ->check(CLI::IsMember(presetNames))
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
  addArrayOption(app, "--domain-diameter-range", p.DomainDiameterRange,
    "Domain sphere diameters MIN MAX in nm (default: the preset's)", "Model");
  this->addGrainOptions(app);
  this->addAbsorptionOptions(app);
  app.add_option("--refractive-index", p.RefractiveIndex, "Refractive index of opal")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--max-placement-attempts", p.MaxPlacementAttempts, "Attempts per domain")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--seed", p.Seed, "Seed of every random choice of the model")
    ->capture_default_str()
    ->group("Model");
  // Each flag of a value a preset may set wins over the preset when given.
  for (const opal::ModelField& field : opal::presetModelFields())
  {
    this->GivenOverPreset.emplace_back(app.get_option(opal::flagOf(field.Property)), &field);
  }
}

// The Voronoi layout and the diameter field (docs/design.md §2.3, §2.9).
void OpalModelOptions::addGrainOptions(CLI::App& app)
{
  opal::ModelParameters& p = this->Parameters;
  addEnumOption(app, "--domain-layout", p.DomainLayout,
    { { "polygons", opal::DomainLayoutKind::Polygons }, { "voronoi", opal::DomainLayoutKind::Voronoi } },
    "Domains as the paper's polygons or as weighted Voronoi grains (polygons)", "Model");
  app.add_option("--voronoi-cell-count", p.VoronoiCellCount, "Voronoi sites in the opal")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--voronoi-weight-spread", p.VoronoiWeightSpread,
       "Additive weights of the Voronoi sites, uniform in [0, SPREAD] mm")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--ordered-fraction", p.OrderedFraction, "Share of the Voronoi cells that are crystal domains, [0, 1]")
    ->capture_default_str()
    ->group("Model");
  app.add_option("--diameter-correlation-length", p.DiameterCorrelationLength,
       "Correlation length of the scattering diameters in mm (0: independent voxels, the paper)")
    ->capture_default_str()
    ->group("Model");
}

// Absorption, the backing layer and scattering inside domains (docs/design.md §2.10), and the
// crystal's indices (§7.2).
void OpalModelOptions::addAbsorptionOptions(CLI::App& app)
{
  opal::ModelParameters& p = this->Parameters;
  const std::pair<const char*, std::pair<double*, const char*>> options[] = {
    { "--body-absorption", { &p.BodyAbsorption, "Absorption of the body in 1/mm at 550 nm (0: none, the paper)" } },
    { "--body-absorption-exponent",
      { &p.BodyAbsorptionExponent,
        "p of the body's absorption mu_a(550) (550/lambda)^p: 0 grey, > 0 absorbs blue (orange body)" } },
    { "--backing-thickness",
      { &p.BackingThickness, "Height in mm of the backing layer at the base (0: none, the paper)" } },
    { "--backing-absorption", { &p.BackingAbsorption, "Grey absorption of the backing layer in 1/mm" } },
    { "--domain-scattering-coefficient",
      { &p.DomainScatteringCoefficient,
        "Scattering inside the domains in 1/mm at 550 nm, as lambda^-4 (0: none, the paper)" } },
    // The crystal of the coupled-wave Bragg model (docs/design.md §7.2).
    { "--sphere-refractive-index", { &p.SphereRefractiveIndex, "Index of the crystal's spheres (silica)" } },
    { "--matrix-refractive-index", { &p.MatrixRefractiveIndex, "Index of the matrix between them (water)" } },
  };
  for (const auto& [flag, target] : options)
  {
    app.add_option(flag, *target.first, target.second)->capture_default_str()->group("Model");
  }
}

opal::ModelParameters OpalModelOptions::parameters() const
{
  opal::ModelParameters resolved = this->Parameters;
  resolved.applyPreset(opal::presetIndexByName(this->Preset));
  for (const auto& [option, field] : this->GivenOverPreset)
  {
    if (option->count() > 0)
    {
      field->Set(resolved, field->Get(this->Parameters));
    }
  }
  return resolved;
}

int OpalModelOptions::presetIndex() const
{
  // A flag that wins over a value the preset lists (fig15's
  // --domain-diameter-range, harlequin's layout, ...): the volume is then
  // recorded (and rebuilt by the source) as custom. A flag for a field the
  // preset only resets to the model's default (--domain-count with fig13)
  // keeps the preset's name: its placement and image size still apply.
  const int index = opal::presetIndexByName(this->Preset);
  const opal::PresetSettings* preset = opal::presetByIndex(index);
  for (const auto& [option, field] : this->GivenOverPreset)
  {
    if (preset && option->count() > 0 && preset->valuesOf(field->Property))
    {
      return opal::CustomPreset;
    }
  }
  return index;
}
