// CLI11 checks of output file names, before any work: the format follows the
// extension, so a name whose extension names no format the option writes is
// refused (exit 2, one line) instead of failing after the render, or writing
// one format under another's name.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

// A validator accepting names that end in one of `extensions` (".png", case ignored).
inline CLI::Validator fileExtension(const std::vector<std::string>& extensions)
{
  std::string list;
  for (const std::string& e : extensions)
  {
    list += (list.empty() ? "" : ", ") + e;
  }
  return CLI::Validator(
    [extensions, list](std::string& name) -> std::string {
      std::string lower = name;
      std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
      for (const std::string& e : extensions)
      {
        if (lower.size() > e.size() && lower.compare(lower.size() - e.size(), e.size(), e) == 0)
        {
          return {};
        }
      }
      return "\"" + name + "\" does not end in one of " + list;
    },
    "FILE (" + list + ")");
}
