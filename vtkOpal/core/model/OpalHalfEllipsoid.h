// The cabochon shape of the paper (§3.1): the half-ellipsoid
// x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1, y >= 0, standing on the base y = 0.
#pragma once

#include <array>

namespace opal
{

class HalfEllipsoid
{
public:
  explicit HalfEllipsoid(const std::array<double, 3>& semiAxes)
    : SemiAxes(semiAxes)
  {
  }

  const std::array<double, 3>& semiAxes() const { return this->SemiAxes; }

  bool contains(const std::array<double, 3>& p) const
  {
    return p[1] >= 0 && this->implicitValue(p) <= 1.0;
  }

  // x^2/a^2 + y^2/b^2 + z^2/c^2.
  double implicitValue(const std::array<double, 3>& p) const
  {
    double f = 0;
    for (int a = 0; a < 3; ++a)
    {
      f += (p[a] * p[a]) / (this->SemiAxes[a] * this->SemiAxes[a]);
    }
    return f;
  }

  // Exact Euclidean signed distance to the surface (dome and base), negative inside.
  double signedDistance(const std::array<double, 3>& p) const;

  // Outward unit normal of the nearest part of the surface: the base's -y if
  // the base is nearer, else the dome's gradient direction.
  std::array<double, 3> outwardNormal(const std::array<double, 3>& p) const;

private:
  std::array<double, 3> SemiAxes;
};

// Distance from a point to the surface of an axis-aligned ellipsoid (n = 3)
// or ellipse (n = 2) centred at the origin.
double distanceToEllipsoidSurface(const double* semiAxes, const double* point, int n);

} // namespace opal
