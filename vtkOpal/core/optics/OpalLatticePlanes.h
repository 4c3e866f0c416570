// The reflecting plane families of a domain's FCC lattice and the domain's
// lattice orientation (docs/design.md §7.1, "The plane families"):
// the four {111}, three {200} and six {220} families with their spacings and
// sphere form factors, and the rotation that stands the crystal's [111] on
// the domain's (111) normal, spun about it.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>

namespace opal
{

// One family of parallel lattice planes (hkl), in the conventional cubic cell
// of edge a = sqrt(2) D of spheres of diameter D touching along <110>.
struct LatticePlane
{
  glm::ivec3 Miller{ 0 };   // (h k l): all odd or all even, FCC's allowed reflections
  glm::dvec3 Normal{ 0.0 }; // unit normal in the crystal (cubic) frame
  double SpacingNm = 0.0;   // d = a / sqrt(h^2 + k^2 + l^2)
  double X = 0.0;           // |G| r = (2 pi / d)(D / 2) = pi D / d, for order 1
};

// 4 {111} + 3 {200} + 6 {220}.
constexpr int FccPlaneCount = 13;

// The families for spheres of diameter D. The first is (111), the stacking
// planes (LatticePlanes = 111, the paper's only family); the rest of {111}
// follow, then {200}, then {220}.
std::array<LatticePlane, FccPlaneCount> fccLatticePlanes(double diameterNm);

// 3 j1(k x) / (k x): eps_kG over 3 f (n_s^2 - n_m^2) for order k of the family
// (its reciprocal vector k G; e.g. order 2 of (111) is (222)).
double fourierRatio(const LatticePlane& plane, int order);

// The rotation from the crystal frame to the model frame that takes [111]/sqrt(3)
// to the domain's unit (111) normal n (by the shortest arc), then turns the
// lattice by `spin` radians about n. n = [111]/sqrt(3) and spin 0 is the identity.
glm::dquat latticeOrientation(const glm::dvec3& normal, double spin);

// The families' unit normals in the model frame, in fccLatticePlanes' order.
std::array<glm::dvec3, FccPlaneCount> modelFrameNormals(
  const std::array<LatticePlane, FccPlaneCount>& planes, const glm::dquat& orientation);

// The orders k = 1 .. K that a family of spacing d reflects at wavelengths of
// shortest lambda_min: lambda_B / k = 2 d n_bar sin theta2 / k >= lambda_min.
// Returns K (0: none). sinGlancing = 1 bounds it over all angles.
int braggOrderCount(double spacingNm, double meanIndex, double sinGlancing, double shortestWavelengthNm);

} // namespace opal
