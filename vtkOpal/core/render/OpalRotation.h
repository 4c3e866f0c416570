// The stone's turn in degrees about x, then y, then z (ModelRotation and a
// preset's placement, docs/design.md §3.2): one convention for the render's
// camera and the Bragg map's light and eye.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <array>

namespace opal
{

inline glm::dmat3 rotationOfDegrees(const std::array<double, 3>& degrees)
{
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(degrees[2]), glm::dvec3(0, 0, 1)) *
    glm::rotate(glm::dmat4(1.0), glm::radians(degrees[1]), glm::dvec3(0, 1, 0)) *
    glm::rotate(glm::dmat4(1.0), glm::radians(degrees[0]), glm::dvec3(1, 0, 0));
  return glm::dmat3(rotation);
}

} // namespace opal
