#include "OpalParameterList.h"

#include "OpalModelParameters.h"
#include "OpalRenderParameters.h"

#include <nlohmann/json.hpp>

namespace
{
template <typename Parameters>
nlohmann::json rowsJson(const std::vector<opal::ParameterRow<Parameters>>& table)
{
  static const char* const typeNames[] = { "int", "double", "bool" };
  auto bound = [](double value) {
    return value == opal::Unbounded || value == -opal::Unbounded ? nlohmann::json() : nlohmann::json(value);
  };
  nlohmann::json rows = nlohmann::json::array();
  for (const opal::ParameterRow<Parameters>& row : table)
  {
    std::vector<double> defaults = row.Get(Parameters());
    if (row.FromVolume)
    {
      defaults.assign(defaults.size(), 0.0);
    }
    rows.push_back({ { "name", row.Name }, { "type", typeNames[static_cast<int>(row.Type)] },
      { "components", row.Components }, { "min", bound(row.Min) }, { "max", bound(row.Max) },
      { "choices", opal::choicesOf(row.Choices) }, { "flag", row.Flag }, { "fromVolume", row.FromVolume },
      { "default", defaults }, { "description", row.Description } });
  }
  return rows;
}
} // namespace

std::string parameterListJson()
{
  const nlohmann::json tables = { { "model", rowsJson(opal::modelParameterRows()) },
    { "render", rowsJson(opal::renderParameterRows()) } };
  return tables.dump(1);
}
