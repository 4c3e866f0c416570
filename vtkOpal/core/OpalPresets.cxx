#include "OpalPresets.h"

namespace opal
{

const std::vector<PresetSettings>& presets()
{
  static const std::vector<PresetSettings> table = {
    { "fig10", { 175.0, 175.0 }, { 640, 480 }, 0.0, std::nullopt },
    { "fig11", { 190.0, 210.0 }, { 640, 480 }, 0.0, std::nullopt },
    { "fig12", { 250.0, 350.0 }, { 640, 480 }, 0.0, std::nullopt },
    { "fig13", { 250.0, 350.0 }, { 640, 480 }, 5.0, std::nullopt },
    { "fig15", { 200.0, 235.0 }, { 300, 300 }, 0.0, std::nullopt },
    { "fig17", { 220.0, 300.0 }, { 300, 300 }, 0.0, std::nullopt },
    // Harlequin: a few large crystal grains in broad, angular patches (cells
    // ~2 mm across), ordered above the percolation threshold so patches join;
    // diameters for green to red play of colour.
    { "harlequin", { 210.0, 300.0 }, { 640, 480 }, 0.0, VoronoiPresetSettings{ 150, 0.3, 0.5 } },
    // Pinfire: many small grains (~0.75 mm) strewn sparsely below the
    // threshold, so they stay isolated specks of every colour.
    { "pinfire", { 200.0, 320.0 }, { 640, 480 }, 0.0, VoronoiPresetSettings{ 3000, 0.05, 0.12 } },
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
