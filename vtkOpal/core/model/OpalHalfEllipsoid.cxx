#include "OpalHalfEllipsoid.h"

#include <algorithm>
#include <cmath>

namespace opal
{

namespace
{
// The closest point is x_i = e_i^2 y_i / (t + e_i^2) where t is the root of
// F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1 (Eberly, "Distance from a point to
// an ellipse, an ellipsoid, or a hyperellipsoid"). F is convex and decreasing
// for t > -min e_i^2, so Newton's method climbs monotonically to the root from
// any start left of it. max_i(-e_i^2 + e_i |y_i|) is such a start; a Newton
// step from any start also lands left of the root, so a guess that is exact
// for spheres, r^2 (rho - 1) with rho^2 = sum y_i^2 / e_i^2 and r the centre's
// distance to the surface along y, costs one step at most. About 4 steps in all.
template <int N>
double distanceToEllipsoid(const double* e, const double* point)
{
  double y[N];
  double e2[N];
  double lowerBound = -1e300;
  double rho2 = 0;
  double length2 = 0;
  double scale = 0;
  for (int i = 0; i < N; ++i)
  {
    // Keep off the symmetry planes, where the closest point can be degenerate.
    y[i] = std::max(std::fabs(point[i]), 1e-12 * e[i]);
    e2[i] = e[i] * e[i];
    lowerBound = std::max(lowerBound, -e2[i] + e[i] * y[i]);
    rho2 += y[i] * y[i] / e2[i];
    length2 += y[i] * y[i];
    scale = std::max(scale, e2[i]);
  }
  double t = std::max(lowerBound, length2 / rho2 * (std::sqrt(rho2) - 1.0));
  // Quadratic convergence: once a step is below 1e-8 of the scale, the root
  // is known to far better than float precision.
  for (int iteration = 0; iteration < 64; ++iteration)
  {
    double f = -1.0;
    double df = 0.0;
    for (int i = 0; i < N; ++i)
    {
      const double inverse = 1.0 / (t + e2[i]);
      const double r = e[i] * y[i] * inverse;
      f += r * r;
      df -= 2.0 * r * r * inverse;
    }
    const double step = f / df;
    t = std::max(lowerBound, t - step);
    if (!(std::fabs(step) > 1e-8 * scale))
    {
      break;
    }
  }
  double distance2 = 0;
  for (int i = 0; i < N; ++i)
  {
    const double x = e2[i] * y[i] / (t + e2[i]);
    distance2 += (x - y[i]) * (x - y[i]);
  }
  return std::sqrt(distance2);
}
} // namespace

double distanceToEllipsoidSurface(const double* semiAxes, const double* point, int n)
{
  return n == 2 ? distanceToEllipsoid<2>(semiAxes, point) : distanceToEllipsoid<3>(semiAxes, point);
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
