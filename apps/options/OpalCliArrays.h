// CLI11 flags of the shapes the parameters have: exactly N values into a
// std::array, or one of an enumeration's names.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <map>
#include <array>
#include <string>
#include <vector>

template <typename T, std::size_t N>
CLI::Option* addArrayOption(
  CLI::App& app, const std::string& name, std::array<T, N>& target, const std::string& help, const std::string& group)
{
  return app
    .add_option_function<std::vector<T>>(
      name, [&target](const std::vector<T>& values) { std::copy(values.begin(), values.end(), target.begin()); },
      help)
    ->expected(static_cast<int>(N))
    ->group(group);
}

// A flag naming one value of an enumeration (case does not matter).
template <typename Enum>
CLI::Option* addEnumOption(CLI::App& app, const std::string& name, Enum& target,
  const std::map<std::string, Enum>& names, const std::string& help, const std::string& group)
{
  return app.add_option(name, target, help)->transform(CLI::CheckedTransformer(names, CLI::ignore_case))->group(group);
}
