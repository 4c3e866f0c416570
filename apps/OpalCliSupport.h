// What the command-line programs share beyond their flags, without VTK: the
// one-line failure message and a progress bar on a terminal.
#pragma once

#include <string>

namespace CLI
{
class App;
}

// CLI11's failure message as one line: "program: what went wrong (see --help)",
// with the numbers allowed where a value did not convert (app: to find the option's type).
std::string oneLineFailure(const std::string& program, const std::string& what, const CLI::App* app = nullptr);

// Parses the arguments; returns -1 to go on, else the exit status: 0 after
// --help, 2 (with one line on stderr) for any bad argument, whatever CLI11's
// own code for it.
int parseArguments(CLI::App& app, int argc, char** argv);

// A labelled progress bar on stderr when stderr is a terminal (silent
// otherwise); each finished bar ends its line once.
class ProgressBar
{
public:
  explicit ProgressBar(std::string label);
  void show(double fraction);

private:
  std::string Label;
  bool Visible;
  bool Finished = false;
  int ShownPercent = -1; // redrawn only when the percentage changes
};
