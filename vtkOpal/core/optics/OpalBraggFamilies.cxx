#include "OpalBraggFamilies.h"

#include "OpalLatticePlanes.h"

#include <cmath>

namespace opal
{

std::vector<BraggFamilyValue> braggFamiliesAt(const std::array<double, 4>& orientation, double diameterNm,
  const std::array<double, 3>& towardLight, const BraggFamilySettings& settings)
{
  const auto planes = fccLatticePlanes(diameterNm);
  const glm::dquat rotation(orientation[0], orientation[1], orientation[2], orientation[3]);
  const auto normals = modelFrameNormals(planes, rotation);
  const glm::dvec3 light(towardLight[0], towardLight[1], towardLight[2]);
  const double meanIndexOfCrystal = meanIndex(settings.Crystal);
  const std::size_t count = settings.LatticePlanes == LatticePlaneSet::Fcc ? planes.size() : 1;
  std::vector<BraggFamilyValue> values(count);
  for (std::size_t f = 0; f < count; ++f)
  {
    CoupledWaveInput input;
    input.SpacingNm = planes[f].SpacingNm;
    input.MeanIndex = meanIndexOfCrystal;
    input.FourierComponent = std::fabs(permittivityFourierComponent(settings.Crystal, planes[f].X));
    input.SinGlancing = std::fabs(glm::dot(light, normals[f]));
    input.Layers = settings.CoherentLayers;
    input.WavelengthNm = 2.0 * input.SpacingNm * input.MeanIndex * input.SinGlancing;
    values[f].Wavelength = input.WavelengthNm;
    values[f].PeakReflectance = input.WavelengthNm > 0 ? coupledWaveReflectance(input).average() : 0.0;
  }
  return values;
}

} // namespace opal
