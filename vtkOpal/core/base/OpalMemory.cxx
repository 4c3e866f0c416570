#include "OpalMemory.h"

#include <cstdio>
#include <unistd.h>

namespace opal
{

std::uint64_t physicalMemoryBytes()
{
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize) : 0;
}

std::string formatBytes(std::uint64_t bytes)
{
  char text[32];
  if (bytes >= (1ull << 30))
  {
    std::snprintf(text, sizeof(text), "%.1f GB", static_cast<double>(bytes) / (1ull << 30));
  }
  else
  {
    std::snprintf(text, sizeof(text), "%.0f MB", static_cast<double>(bytes) / (1ull << 20));
  }
  return text;
}

} // namespace opal
