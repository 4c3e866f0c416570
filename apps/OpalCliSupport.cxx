#include "OpalCliSupport.h"

#include <algorithm>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <unistd.h>
#include <utility>

std::string oneLineFailure(const std::string& program, const std::string& what)
{
  return program + ": " + what + " (see --help)\n";
}

int parseArguments(CLI::App& app, int argc, char** argv)
{
  try
  {
    app.parse(argc, argv);
    return -1;
  }
  catch (const CLI::CallForHelp& help)
  {
    return app.exit(help);
  }
  catch (const CLI::ParseError& error)
  {
    app.exit(error); // prints the one line of app.failure_message
    return 2;
  }
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
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100 + 0.5);
  if (percent == this->ShownPercent && fraction < 1.0)
  {
    return;
  }
  this->ShownPercent = percent;
  const int filled = percent * Width / 100;
  std::fprintf(stderr, "\r%-10s [%s%s] %3d%%", this->Label.c_str(),
    std::string(static_cast<std::size_t>(filled), '#').c_str(),
    std::string(static_cast<std::size_t>(Width - filled), ' ').c_str(), percent);
  if (fraction >= 1.0)
  {
    std::fprintf(stderr, "\n");
    this->Finished = true;
  }
  std::fflush(stderr);
}
