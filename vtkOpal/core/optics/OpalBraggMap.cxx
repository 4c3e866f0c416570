#include "OpalBraggMap.h"

#include "OpalColourimetry.h"
#include "OpalOptics.h"
#include "OpalRotation.h"

#include <glm/glm.hpp>

#include <cmath>

namespace opal
{

BraggMapSettings inStoneFrame(const BraggMapSettings& settings)
{
  const glm::dmat3 toStone = glm::transpose(rotationOfDegrees(settings.ModelRotation));
  const auto turn = [&toStone](const std::array<double, 3>& p) {
    const glm::dvec3 turned = toStone * glm::dvec3(p[0], p[1], p[2]);
    return std::array<double, 3>{ turned.x, turned.y, turned.z };
  };
  BraggMapSettings turned = settings;
  turned.LightPosition = turn(settings.LightPosition);
  turned.EyePosition = turn(settings.EyePosition);
  turned.ModelRotation = { 0.0, 0.0, 0.0 };
  return turned;
}

BraggMapValue braggMapAt(const std::array<double, 3>& position, const std::array<double, 3>& normal,
  double diameterNm, const BraggMapSettings& s)
{
  const glm::dvec3 p(position[0], position[1], position[2]);
  const glm::dvec3 n = glm::normalize(glm::dvec3(normal[0], normal[1], normal[2]));
  const glm::dvec3 towardLight =
    glm::normalize(glm::dvec3(s.LightPosition[0], s.LightPosition[1], s.LightPosition[2]) - p);
  // The glancing angle theta1 between the light and the lattice planes.
  const double glancing = std::asin(std::min(1.0, std::fabs(glm::dot(towardLight, n))));
  BraggMapValue value;
  value.Wavelength = s.CoupledWaveMeanIndex > 0
    ? 2.0 * diameterNm * std::sqrt(2.0 / 3.0) * s.CoupledWaveMeanIndex * std::sin(glancing) / s.BraggOrder
    : braggSnellWavelength(diameterNm, s.RefractiveIndex, glancing, s.BraggOrder);
  const bool visible = value.Wavelength >= s.VisibleRange[0] && value.Wavelength <= s.VisibleRange[1];
  double weight = 1.0;
  if (s.MosaicSpread > 0)
  {
    // Gaussian in the angle between the lattice normal and the bisector of
    // the directions to light and eye (as the render's mosaicWeight).
    const glm::dvec3 towardEye = glm::normalize(glm::dvec3(s.EyePosition[0], s.EyePosition[1], s.EyePosition[2]) - p);
    const glm::dvec3 bisector = glm::normalize(towardLight + towardEye);
    const double angle = std::acos(std::min(1.0, std::fabs(glm::dot(n, bisector))));
    const double spread = s.MosaicSpread * Pi / 180.0;
    weight = std::exp(-0.5 * (angle / spread) * (angle / spread));
  }
  value.Visible = visible ? weight : 0.0;
  if (visible)
  {
    value.Colour = wavelengthToSrgb8(value.Wavelength);
  }
  return value;
}

} // namespace opal
