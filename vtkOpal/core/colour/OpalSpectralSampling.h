// Wavelength sampling of the spectral render: bins of a given step across a
// range, each carrying the bin-averaged CIE 1931 2-degree colour-matching
// functions and D65 (official tables in data/), so results do not depend on
// the step. D65 is normalised so that sum D65 y-bar d(lambda) = 1.
#pragma once

#include <vector>

namespace opal
{

struct WavelengthBin
{
  double Lambda;        // bin centre, nm
  double Width;         // nm
  double RayleighScale; // (550 / lambda)^4: mu_s(lambda) = mu_s(550) * scale
  double D65;           // normalised relative power (luminance 1 over the bins)
  double D65Scale;      // the normalisation: D65 = CIE table value x D65Scale
  double XBar, YBar, ZBar;
};

// Bins centred at lo, lo + step, ... up to hi (inclusive within step/1000).
std::vector<WavelengthBin> sampleWavelengths(double lo, double hi, double step);

// How many bins sampleWavelengths gives (without computing them).
int wavelengthBinCount(double lo, double hi, double step);

// The official tables, linearly interpolated (CMFs 360-830 nm at 1 nm, zero
// outside; D65 300-780 nm at 5 nm, held constant beyond its ends).
double cieColourMatching(int component, double lambda);
double cieD65(double lambda);

} // namespace opal
