// Writes a file under a temporary name in the same folder and renames it into
// place, so an earlier file is never replaced by a partial one.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

// Calls write(temporaryPath); on success renames it to path. Returns an empty
// string on success, else the reason; the temporary file never survives.
std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write);
