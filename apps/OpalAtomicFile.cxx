#include "OpalAtomicFile.h"

#include <system_error>
#include <unistd.h>

std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write)
{
  // Keep the extension last: writers pick the format from it.
  std::filesystem::path temporary = path;
  temporary.replace_filename(
    "." + path.stem().string() + ".partial-" + std::to_string(::getpid()) + path.extension().string());
  if (!write(temporary.string()))
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "could not write " + path.string();
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error)
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "could not move the finished file to " + path.string() + ": " + error.message();
  }
  return {};
}
