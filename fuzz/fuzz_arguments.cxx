// libFuzzer target: opal-render's argument parsing and parameter validation.
// The input is split into arguments at newlines; every argument list must
// either be refused (CLI11's error, or a validation message naming a
// parameter) or give parameters that validate, never crash or hang. The
// render itself is not run.
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalRenderOptions.h"
#include "OpalRenderParameters.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<std::string> arguments;
  std::string current;
  for (std::size_t i = 0; i < size && arguments.size() < 64; ++i)
  {
    if (data[i] == '\n')
    {
      arguments.push_back(current);
      current.clear();
    }
    else
    {
      current += static_cast<char>(data[i]);
    }
  }
  arguments.push_back(current);

  CLI::App app{ "opal-render (fuzzed)" };
  OpalModelOptions model;
  model.addTo(app);
  OpalRenderOptions render;
  render.addTo(app);
  std::vector<std::string> outputs;
  app.add_option("-o,--output", outputs);
  // CLI11 parses a reversed vector (it pops arguments from the back).
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
  try
  {
    app.parse(reversed);
  }
  catch (const CLI::ParseError&)
  {
    return 0; // refused with CLI11's message: fine
  }
  const opal::ModelParameters parameters = model.parameters();
  const std::string modelError = opal::validate(parameters);
  const opal::RenderParameters renderParameters = render.parameters(model.presetName(), model.refractiveIndex());
  const std::string renderError = opal::validate(renderParameters);
  if (modelError.empty() && renderError.empty() && opal::wavelengthCount(renderParameters) < 1)
  {
    std::abort(); // valid parameters must give at least one wavelength
  }
  return 0;
}
