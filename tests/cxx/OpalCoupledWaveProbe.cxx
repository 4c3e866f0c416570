// Prints OpalCore's coupled-wave reflectance (docs/design.md §7.1) at the
// wavelengths (nm) read from standard input, one line "lambda R_s R_p
// R_average" each, for tests/python/TestOpalCoupledWave.py to hold against a
// transfer-matrix computation of the same index profile.
//
//   OpalCoupledWaveProbe --spacing-nm D --mean-index N --fourier-component E
//     --sin-glancing S --layers L [--order K] < wavelengths
#include "OpalCoupledWave.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

namespace
{
int usage(const char* why)
{
  std::fprintf(stderr,
    "OpalCoupledWaveProbe: %s\nusage: OpalCoupledWaveProbe --spacing-nm D --mean-index N "
    "--fourier-component E --sin-glancing S --layers L [--order K] < wavelengths\n",
    why);
  return 2;
}

bool parseNumber(const char* text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0';
}
} // namespace

int main(int argc, char* argv[])
{
  // Every option but --order is required: NaN until given.
  const double unset = std::nan("");
  std::map<std::string, double> options{ { "--spacing-nm", unset }, { "--mean-index", unset },
    { "--fourier-component", unset }, { "--sin-glancing", unset }, { "--layers", unset },
    { "--order", 1.0 } };
  for (int i = 1; i < argc; ++i)
  {
    const std::string name = argv[i];
    const auto option = options.find(name);
    if (option == options.end())
    {
      return usage(("unknown option " + name).c_str());
    }
    if (i + 1 >= argc || !parseNumber(argv[++i], option->second))
    {
      return usage(("a number after " + name).c_str());
    }
  }
  for (const auto& option : options)
  {
    if (std::isnan(option.second))
    {
      return usage(("missing " + option.first).c_str());
    }
  }
  opal::CoupledWaveInput in;
  in.SpacingNm = options["--spacing-nm"];
  in.MeanIndex = options["--mean-index"];
  in.FourierComponent = options["--fourier-component"];
  in.SinGlancing = options["--sin-glancing"];
  in.Layers = options["--layers"];
  in.Order = static_cast<int>(options["--order"]);
  double lambda = 0;
  while (std::scanf("%lf", &lambda) == 1)
  {
    in.WavelengthNm = lambda;
    const opal::CoupledWaveReflectance r = opal::coupledWaveReflectance(in);
    std::printf("%.17g %.17g %.17g %.17g\n", lambda, r.S, r.P, r.average());
  }
  return 0;
}
