// CLI11 flags that take exactly N values into a std::array.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
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
