#include "OpalPresets.h"

namespace opal
{

const std::vector<PresetSettings>& presets()
{
  static const std::vector<PresetSettings> table = {
    { "fig10", { 175.0, 175.0 }, { 640, 480 }, 0.0 },
    { "fig11", { 190.0, 210.0 }, { 640, 480 }, 0.0 },
    { "fig12", { 250.0, 350.0 }, { 640, 480 }, 0.0 },
    { "fig13", { 250.0, 350.0 }, { 640, 480 }, 5.0 },
    { "fig15", { 200.0, 235.0 }, { 300, 300 }, 0.0 },
    { "fig17", { 220.0, 300.0 }, { 300, 300 }, 0.0 },
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
