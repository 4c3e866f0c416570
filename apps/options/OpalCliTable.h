// A parameter table's row as a CLI11 flag (docs/design.md §1.1): a number or
// N numbers, an enumeration's name (or its value), or a switch, with the
// row's description and its default from the parameters' struct. Numbers are
// read strictly (OpalCliNumbers.h); a whole number's range is checked here, as
// CLI11 converts it to an int, a fraction's is validate's: either refusal
// names the parameter as every layer does.
#pragma once

#include "OpalCliNumbers.h"
#include "OpalParameterRow.h"

#include <CLI/CLI.hpp>

#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

template <typename Parameters>
std::string defaultText(const opal::ParameterRow<Parameters>& row)
{
  if (row.FromVolume)
  {
    return " (default: the volume's)";
  }
  const std::vector<double> values = row.Get(Parameters());
  if (row.Type == opal::ParameterType::Bool)
  {
    return values.at(0) != 0 ? " (default: on)" : " (default: off)";
  }
  std::ostringstream text;
  text << " (default:";
  const std::vector<std::string> names = opal::choicesOf(row.Choices);
  for (const double v : values)
  {
    text << " ";
    if (names.empty())
    {
      text << v;
    }
    else
    {
      text << names.at(static_cast<std::size_t>(v));
    }
  }
  text << ")";
  return text.str();
}

template <typename Number, typename Parameters>
CLI::Option* addNumbersOption(CLI::App& app, const opal::ParameterRow<Parameters>& row, Parameters& target,
  const std::string& help)
{
  auto set = row.Set;
  return app
    .add_option_function<std::vector<Number>>(
      row.Flag,
      [&target, set](const std::vector<Number>& values) { set(target, std::vector<double>(values.begin(), values.end())); },
      help)
    ->expected(row.Components)
    ->transform(opalcli::numberCheck(row.Name, row.Min, row.Max, std::is_integral_v<Number>));
}

template <typename Parameters>
CLI::Option* addRowOption(
  CLI::App& app, const opal::ParameterRow<Parameters>& row, Parameters& target, const std::string& group)
{
  const std::string help = std::string(row.Description) + defaultText(row);
  auto set = row.Set;
  CLI::Option* option = nullptr;
  if (row.Type == opal::ParameterType::Bool)
  {
    option = app.add_flag_callback(row.Flag, [&target, set]() { set(target, { 1.0 }); }, help);
  }
  else if (*row.Choices != '\0')
  {
    std::map<std::string, int> names;
    const std::vector<std::string> choices = opal::choicesOf(row.Choices);
    for (std::size_t i = 0; i < choices.size(); ++i)
    {
      names.emplace(choices[i], static_cast<int>(i));
    }
    option = app.add_option_function<int>(row.Flag, [&target, set](int value) { set(target, { double(value) }); }, help)
               ->transform(CLI::CheckedTransformer(names, CLI::ignore_case));
  }
  else if (row.Type == opal::ParameterType::Int)
  {
    option = addNumbersOption<int>(app, row, target, help);
  }
  else
  {
    option = addNumbersOption<double>(app, row, target, help);
  }
  return option->group(group);
}
