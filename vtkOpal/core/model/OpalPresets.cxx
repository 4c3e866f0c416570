#include "OpalPresets.h"

#include "OpalModelParameters.h"

#include <utility>

namespace opal
{

namespace
{
// A Voronoi preset's values (docs/design.md §2.9): the layout and its grains.
std::vector<PresetValue> voronoi(
  std::vector<double> diameterRange, int cellCount, double weightSpread, double orderedFraction)
{
  return { { "DomainDiameterRange", std::move(diameterRange) },
    { "DomainLayout", { static_cast<double>(DomainLayoutKind::Voronoi) } },
    { "VoronoiCellCount", { static_cast<double>(cellCount) } }, { "VoronoiWeightSpread", { weightSpread } },
    { "OrderedFraction", { orderedFraction } } };
}
} // namespace

const std::vector<double>* PresetSettings::valuesOf(const char* property) const
{
  for (const PresetValue& value : this->Model)
  {
    if (std::string(property) == value.Property)
    {
      return &value.Values;
    }
  }
  return nullptr;
}

const std::vector<PresetSettings>& presets()
{
  static const std::vector<PresetSettings> table = {
    { "fig10", { 640, 480 }, 0.0, { { "DomainDiameterRange", { 175.0, 175.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    { "fig11", { 640, 480 }, 0.0, { { "DomainDiameterRange", { 190.0, 210.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    { "fig12", { 640, 480 }, 0.0, { { "DomainDiameterRange", { 250.0, 350.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    { "fig13", { 640, 480 }, 5.0, { { "DomainDiameterRange", { 250.0, 350.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    { "fig15", { 300, 300 }, 0.0, { { "DomainDiameterRange", { 200.0, 235.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    { "fig17", { 300, 300 }, 0.0, { { "DomainDiameterRange", { 220.0, 300.0 } } },
      BraggModelKind::Paper, LatticePlaneSet::Stacking111, ScatteringOrdersKind::Single },
    // Harlequin: a few large crystal grains in broad, angular patches (cells
    // ~2 mm across), ordered above the percolation threshold so patches join;
    // diameters for green to red play of colour.
    { "harlequin", { 640, 480 }, 0.0, voronoi({ 210.0, 300.0 }, 150, 0.3, 0.5) },
    // Pinfire: many small grains (~0.75 mm) strewn sparsely below the
    // threshold, so they stay isolated specks of every colour.
    { "pinfire", { 640, 480 }, 0.0, voronoi({ 200.0, 320.0 }, 3000, 0.05, 0.12) },
    // The kinds of opal (docs/design.md §2.11): the body's scattering and
    // absorption, the backing and the domains' spheres; rendered with the
    // coupled-wave reflectance of every FCC plane family (§7.2).
    // White opal (Coober Pedy): a milky body, pastel play of colour.
    { "white-opal", { 640, 480 }, 0.0, { { "ScatteringVolumeFraction", { 0.2 } },
      { "DomainDiameterRange", { 200.0, 300.0 } } },
      BraggModelKind::CoupledWave, LatticePlaneSet::Fcc },
    // Black opal (Lightning Ridge): a thin, nearly clear colour bar on dark
    // potch; large domains flash over broad patches.
    { "black-opal", { 640, 480 }, 0.0, { { "ScatteringVolumeFraction", { 0.04 } }, { "BodyAbsorption", { 0.25 } },
      { "BackingThickness", { 4.0 } }, { "BackingAbsorption", { 5.0 } },
      { "DomainDiameterRange", { 230.0, 320.0 } }, { "DomainRadiusRange", { 0.8, 2.0 } } },
      BraggModelKind::CoupledWave, LatticePlaneSet::Fcc },
    // Crystal opal: a transparent body, colour seen deep inside.
    { "crystal-opal", { 640, 480 }, 0.0, { { "ScatteringVolumeFraction", { 0.03 } },
      { "DomainDiameterRange", { 200.0, 300.0 } } },
      BraggModelKind::CoupledWave, LatticePlaneSet::Fcc },
    // Fire opal (Mexico): a clear body coloured orange by iron oxides that
    // absorb blue (mu_a ~ lambda^-6), little play of colour.
    { "fire-opal", { 640, 480 }, 0.0, { { "ScatteringVolumeFraction", { 0.05 } }, { "BodyAbsorption", { 0.4 } },
      { "BodyAbsorptionExponent", { 6.0 } }, { "DomainCount", { 80.0 } },
      { "DomainDiameterRange", { 240.0, 320.0 } } },
      BraggModelKind::CoupledWave, LatticePlaneSet::Fcc },
    // Boulder opal (Queensland): a seam of opal on brown ironstone: a thick
    // dark backing under a thin, slightly milky layer.
    { "boulder-opal", { 640, 480 }, 0.0, { { "ScatteringVolumeFraction", { 0.1 } }, { "BodyAbsorption", { 0.05 } },
      { "BackingThickness", { 5.5 } }, { "BackingAbsorption", { 4.0 } },
      { "DomainDiameterRange", { 220.0, 330.0 } } },
      BraggModelKind::CoupledWave, LatticePlaneSet::Fcc },
  };
  return table;
}

const PresetSettings* presetByIndex(int index)
{
  const auto& table = presets();
  if (index < 1 || index > static_cast<int>(table.size()))
  {
    return nullptr;
  }
  return &table[static_cast<std::size_t>(index - 1)];
}

int presetIndexByName(const std::string& name)
{
  if (name == "custom")
  {
    return CustomPreset;
  }
  const auto& table = presets();
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    if (name == table[i].Name)
    {
      return static_cast<int>(i) + 1;
    }
  }
  return -1;
}

std::string presetNameList()
{
  std::string list = "custom";
  for (const auto& preset : presets())
  {
    list += ", ";
    list += preset.Name;
  }
  return list;
}

} // namespace opal
