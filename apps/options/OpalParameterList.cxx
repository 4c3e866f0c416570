#include "OpalParameterList.h"

#include "OpalRenderParameters.h"

#include <nlohmann/json.hpp>

std::string renderParameterListJson()
{
  static const char* const typeNames[] = { "int", "double", "bool" };
  nlohmann::json rows = nlohmann::json::array();
  for (const opal::ParameterRow<opal::RenderParameters>& row : opal::renderParameterRows())
  {
    std::vector<double> defaults = row.Get(opal::RenderParameters());
    if (row.FromVolume)
    {
      defaults.assign(defaults.size(), 0.0);
    }
    rows.push_back({ { "name", row.Name }, { "type", typeNames[static_cast<int>(row.Type)] },
      { "components", row.Components }, { "min", row.Min == -opal::Unbounded ? nlohmann::json() : nlohmann::json(row.Min) },
      { "max", row.Max == opal::Unbounded ? nlohmann::json() : nlohmann::json(row.Max) },
      { "choices", opal::choicesOf(row.Choices) }, { "flag", row.Flag }, { "fromVolume", row.FromVolume },
      { "default", defaults }, { "description", row.Description } });
  }
  return rows.dump(1);
}
