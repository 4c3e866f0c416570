#include "OpalCliSupport.h"

#include <algorithm>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <unistd.h>
#include <utility>

namespace
{
// What a number of the option's type may be, for a value that did not
// convert ("Could not convert: --seed = -1"); empty if that is not the error.
std::string allowedNumbers(const CLI::App* app, const std::string& what)
{
  const std::string prefix = "Could not convert: ";
  const std::size_t equals = what.find(" = ");
  if (!app || what.rfind(prefix, 0) != 0 || equals == std::string::npos)
  {
    return {};
  }
  const CLI::Option* option = app->get_option_no_throw(what.substr(prefix.size(), equals - prefix.size()));
  const std::string type = option ? option->get_type_name() : "";
  if (type.rfind("INT", 0) == 0)
  {
    return ": a whole number from -2147483648 to 2147483647";
  }
  return type.rfind("FLOAT", 0) == 0 ? ": a number" : "";
}
} // namespace

std::string oneLineFailure(const std::string& program, const std::string& what, const CLI::App* app)
{
  return program + ": " + what + allowedNumbers(app, what) + " (see --help)\n";
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
  catch (const CLI::Success&)
  {
    return 0; // a flag that did its work and ends the program (--list-parameters)
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
