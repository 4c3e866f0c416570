#include "OpalRenderImage.h"

#include <algorithm>
#include <cmath>

namespace opal
{

std::string nonFiniteArray(const RenderImage& image)
{
  const std::pair<const char*, const std::vector<float>*> arrays[] = { { "Radiance", &image.Radiance },
    { "XYZ", &image.XYZ }, { "DominantBraggWavelength", &image.DominantBraggWavelength }, { "Depth", &image.Depth },
    { "Spectrum", &image.Spectrum } };
  for (const auto& [name, values] : arrays)
  {
    if (!std::all_of(values->begin(), values->end(), [](float v) { return std::isfinite(v); }))
    {
      return name;
    }
  }
  return std::isfinite(image.Exposure) ? std::string() : "Exposure";
}

} // namespace opal
