#include "OpalHalfEllipsoid.h"

#include <algorithm>
#include <cmath>

namespace opal
{

double distanceToEllipsoidSurface(const double* e, const double* point, int n)
{
  // The closest point is x_i = e_i^2 y_i / (t + e_i^2) where t is the root of
  // F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1 (Eberly, "Distance from a point to
  // an ellipse, an ellipsoid, or a hyperellipsoid"). F is convex and decreasing
  // for t > -min e_i^2, so Newton's method started left of the root, at the
  // lower bound max_i(-e_i^2 + e_i |y_i|), climbs to it monotonically.
  double y[3];
  double t = -1e300;
  for (int i = 0; i < n; ++i)
  {
    // Keep off the symmetry planes, where the closest point can be degenerate.
    y[i] = std::max(std::fabs(point[i]), 1e-12 * e[i]);
    t = std::max(t, -e[i] * e[i] + e[i] * y[i]);
  }
  for (int iteration = 0; iteration < 64; ++iteration)
  {
    double f = -1.0;
    double df = 0.0;
    for (int i = 0; i < n; ++i)
    {
      const double r = e[i] * y[i] / (t + e[i] * e[i]);
      f += r * r;
      df -= 2.0 * r * r / (t + e[i] * e[i]);
    }
    const double step = f / df;
    t -= step;
    if (!(std::fabs(step) > 1e-13 * (1.0 + std::fabs(t))))
    {
      break;
    }
  }
  double distance2 = 0;
  for (int i = 0; i < n; ++i)
  {
    const double x = e[i] * e[i] * y[i] / (t + e[i] * e[i]);
    distance2 += (x - y[i]) * (x - y[i]);
  }
  return std::sqrt(distance2);
}

double HalfEllipsoid::signedDistance(const std::array<double, 3>& p) const
{
  const double* e = this->SemiAxes.data();
  if (p[1] >= 0)
  {
    const double dome = distanceToEllipsoidSurface(e, p.data(), 3);
    if (this->implicitValue(p) <= 1.0)
    {
      return -std::min(dome, p[1]);
    }
    return dome;
  }
  // Below the base: the nearest point lies on the base's elliptic disc.
  const double xz[2] = { p[0], p[2] };
  const double exz[2] = { e[0], e[2] };
  if (xz[0] * xz[0] / (exz[0] * exz[0]) + xz[1] * xz[1] / (exz[1] * exz[1]) <= 1.0)
  {
    return -p[1];
  }
  const double rim = distanceToEllipsoidSurface(exz, xz, 2);
  return std::sqrt(rim * rim + p[1] * p[1]);
}

std::array<double, 3> HalfEllipsoid::outwardNormal(const std::array<double, 3>& p) const
{
  const double dome = distanceToEllipsoidSurface(this->SemiAxes.data(), p.data(), 3);
  if (p[1] < dome)
  {
    return { 0.0, -1.0, 0.0 };
  }
  std::array<double, 3> g;
  double length2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    g[a] = p[a] / (this->SemiAxes[a] * this->SemiAxes[a]);
    length2 += g[a] * g[a];
  }
  const double inverse = length2 > 0 ? 1.0 / std::sqrt(length2) : 0.0;
  return { g[0] * inverse, g[1] * inverse, g[2] * inverse };
}

} // namespace opal
