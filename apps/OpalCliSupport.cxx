#include "OpalCliSupport.h"

#include <cstdio>
#include <unistd.h>
#include <utility>

std::string oneLineFailure(const std::string& program, const std::string& what)
{
  return program + ": " + what + " (see --help)\n";
}

ProgressBar::ProgressBar(std::string label)
  : Label(std::move(label))
  , Visible(::isatty(STDERR_FILENO) != 0)
{
}

void ProgressBar::show(double fraction)
{
  if (!this->Visible || this->Finished)
  {
    return;
  }
  constexpr int Width = 40;
  const int filled = static_cast<int>(fraction * Width + 0.5);
  std::fprintf(stderr, "\r%-10s [%s%s] %3d%%", this->Label.c_str(),
    std::string(static_cast<std::size_t>(filled), '#').c_str(),
    std::string(static_cast<std::size_t>(Width - filled), ' ').c_str(), static_cast<int>(fraction * 100 + 0.5));
  if (fraction >= 1.0)
  {
    std::fprintf(stderr, "\n");
    this->Finished = true;
  }
  std::fflush(stderr);
}
