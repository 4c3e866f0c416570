// The "Visible spectrum" colour map (380-780 nm to the sRGB colour of each
// wavelength) becomes ParaView's default for the arrays that hold
// wavelengths, as site-level settings registered when the plugin loads, so a
// user's own choice (saved at a higher priority) still wins.
#include "OpalColourimetry.h"

#include "vtkSMSettings.h"

#include <sstream>

namespace
{
std::string visibleSpectrumSettings()
{
  std::ostringstream points;
  for (int lambda = 380; lambda <= 780; lambda += 5)
  {
    const auto rgb = opal::wavelengthToSrgb8(lambda);
    points << (lambda > 380 ? ", " : "") << lambda << ", " << rgb[0] / 255.0 << ", " << rgb[1] / 255.0 << ", "
           << rgb[2] / 255.0;
  }
  std::ostringstream json;
  json << "{ \"array_lookup_tables\": {";
  const char* arrays[] = { "BraggWavelength", "BraggLambdaMax", "BraggLambdaMin", "DominantBraggWavelength" };
  for (std::size_t i = 0; i < 4; ++i)
  {
    json << (i ? ", " : "") << "\"" << arrays[i] << "\": { \"PVLookupTable\": { \"RGBPoints\": [" << points.str()
         << "], \"ColorSpace\": 0, \"AutomaticRescaleRangeMode\": -1, \"NanColor\": [0, 0, 0] }, "
         << "\"Title\": \"" << arrays[i] << " (nm)\" }";
  }
  json << "} }";
  return json.str();
}

// Registered once, when the plugin's library is loaded.
const bool registered = vtkSMSettings::GetInstance()->AddCollectionFromString(visibleSpectrumSettings(), 0.5);
} // namespace
