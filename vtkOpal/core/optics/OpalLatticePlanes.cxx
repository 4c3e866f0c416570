#include "OpalLatticePlanes.h"

#include "OpalCoupledWave.h"
#include "OpalOptics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace opal
{

namespace
{
// The plane normals' Miller indices. (111) first: it is the stacking plane the
// domain's drawn normal stands for; the (hkl) and (-h-k-l) are one family.
constexpr std::array<std::array<int, 3>, FccPlaneCount> FccMiller{ {
  { 1, 1, 1 }, { -1, 1, 1 }, { 1, -1, 1 }, { 1, 1, -1 },                          // {111}
  { 2, 0, 0 }, { 0, 2, 0 }, { 0, 0, 2 },                                          // {200}
  { 2, 2, 0 }, { 2, -2, 0 }, { 2, 0, 2 }, { 2, 0, -2 }, { 0, 2, 2 }, { 0, 2, -2 } // {220}
} };

// The crystal's [111] direction, which the orientation stands on the domain's normal.
const glm::dvec3 Crystal111 = glm::dvec3(1.0) / std::sqrt(3.0);
} // namespace

std::array<LatticePlane, FccPlaneCount> fccLatticePlanes(double diameterNm)
{
  const double cell = std::sqrt(2.0) * diameterNm;
  std::array<LatticePlane, FccPlaneCount> planes;
  for (std::size_t i = 0; i < planes.size(); ++i)
  {
    const glm::ivec3 m(FccMiller[i][0], FccMiller[i][1], FccMiller[i][2]);
    const glm::dvec3 g(m);
    planes[i].Miller = m;
    planes[i].Normal = glm::normalize(g);
    planes[i].SpacingNm = cell / glm::length(g);
    // |G| = 2 pi / d and r = D / 2, so x = pi D / d = pi sqrt(h^2 + k^2 + l^2) / sqrt(2).
    planes[i].X = Pi * diameterNm / planes[i].SpacingNm;
  }
  return planes;
}

double fourierRatio(const LatticePlane& plane, int order)
{
  return sphereFormFactor(order * plane.X);
}

// Shortest arc: the quaternion (1 + cos, sin * axis) = (1 + a.n, a x n),
// normalised, turns a onto n to ~1e-16 / (angle from -a); at n = -a (within
// 1.4e-7 rad) any axis perpendicular to a will do, [1 -1 0] does. -[111] lies
// 35 degrees below the plane y = 0, far from the paper's upward-turned normals.
glm::dquat latticeOrientation(const glm::dvec3& normal, double spin)
{
  const glm::dvec3 n = glm::normalize(normal);
  const double w = 1.0 + glm::dot(Crystal111, n);
  const glm::dquat stand = w > 1e-14
    ? glm::normalize(glm::dquat(w, glm::cross(Crystal111, n)))
    : glm::angleAxis(Pi, glm::normalize(glm::dvec3(1.0, -1.0, 0.0)));
  return glm::angleAxis(spin, n) * stand;
}

std::array<glm::dvec3, FccPlaneCount> modelFrameNormals(
  const std::array<LatticePlane, FccPlaneCount>& planes, const glm::dquat& orientation)
{
  std::array<glm::dvec3, FccPlaneCount> normals;
  for (std::size_t i = 0; i < planes.size(); ++i)
  {
    normals[i] = orientation * planes[i].Normal;
  }
  return normals;
}

int braggOrderCount(double spacingNm, double meanIndex, double sinGlancing, double shortestWavelengthNm)
{
  if (shortestWavelengthNm <= 0.0)
  {
    return 0;
  }
  const double orders = std::floor(2.0 * spacingNm * meanIndex * sinGlancing / shortestWavelengthNm);
  return orders > 0.0 ? static_cast<int>(std::min(orders, double(std::numeric_limits<int>::max()))) : 0;
}

} // namespace opal
