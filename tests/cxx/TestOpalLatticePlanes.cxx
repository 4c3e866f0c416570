// The FCC lattice planes and their coupled-wave reflectance (docs/design.md
// §7.1): the sphere form factors 3 j1(x)/x of (111), (200),
// (220) and (222) against the closed form written out here, the spacings and
// the angles between the families, the lattice orientation (it stands [111]
// on the domain's normal and the spin turns the other families about it), the
// orders, and the reflectance's closed forms: tanh^2(kappa L) at the Bragg
// wavelength, coupled-mode theory's sinh / sin forms on either side of the band edge,
// continuity at the edge, symmetry, decay off the band, no NaN at the limits.
// The band's shape against an exact transfer-matrix computation is
// tests/python/TestOpalCoupledWave.py.
#include "OpalTestHarness.h"

#include "OpalCoupledWave.h"
#include "OpalDomainLayout.h"
#include "OpalLatticePlanes.h"
#include "OpalOptics.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
constexpr double DiameterNm = 250.0;

bool near(double a, double b, double tolerance)
{
  return std::fabs(a - b) <= tolerance;
}

// 3 j1(x)/x for |G| = 2 pi sqrt(h^2 + k^2 + l^2) / a, r = D / 2, a = sqrt(2) D.
double closedFormRatio(int h, int k, int l)
{
  const double a = std::sqrt(2.0) * DiameterNm;
  const double x = 2.0 * opal::Pi * std::sqrt(double(h * h + k * k + l * l)) / a * (DiameterNm / 2.0);
  return 3.0 * (std::sin(x) - x * std::cos(x)) / (x * x * x);
}

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  // A plane family's normal has no sign: the angle between families is at most 90 degrees.
  return std::acos(std::min(1.0, std::fabs(glm::dot(a, b)))) * 180.0 / opal::Pi;
}

void checkFourierRatios()
{
  const auto planes = opal::fccLatticePlanes(DiameterNm);
  struct Case
  {
    int Plane, Order, H, K, L;
    double X, Design; // x and the value docs/design.md §7.1 quotes, to 3 digits
  };
  // (222) is order 2 of (111): -0.0015.
  const Case cases[] = { { 0, 1, 1, 1, 1, 3.8476, 0.1200 }, { 4, 1, 2, 0, 0, 4.4429, 0.00749 },
    { 7, 1, 2, 2, 0, 2 * opal::Pi, -0.0760 }, { 0, 2, 2, 2, 2, 7.6953, -0.00150 } };
  for (const Case& c : cases)
  {
    const std::string name = "(" + std::to_string(c.H) + std::to_string(c.K) + std::to_string(c.L) + ")";
    const opal::LatticePlane& plane = planes[static_cast<std::size_t>(c.Plane)];
    const double ratio = opal::fourierRatio(plane, c.Order);
    const double closed = closedFormRatio(c.H, c.K, c.L);
    OPAL_CHECK(near(ratio, closed, 1e-14),
      name + " form factor " + std::to_string(ratio) + ", closed form " + std::to_string(closed));
    OPAL_CHECK(near(ratio, c.Design, 5e-5), name + " form factor " + std::to_string(ratio));
    OPAL_CHECK(near(c.Order * plane.X, c.X, 1e-4), name + " x = |G| r");
  }
  // docs/design.md §7.1: silica/water |eps_111| ~ 0.0296, rho = eps_G / eps_bar ~ 1.5%; silica/air ~ 5.4%.
  const opal::ColloidalCrystal water;
  const double eps111 = opal::permittivityFourierComponent(water, planes[0].X);
  OPAL_CHECK(near(eps111, 0.0296, 1e-4), "silica/water eps_111 " + std::to_string(eps111));
  OPAL_CHECK(near(eps111 / opal::meanPermittivity(water), 0.0147, 1e-4), "silica/water eps_111 / eps_bar");
  opal::ColloidalCrystal air;
  air.MatrixIndex = 1.0;
  OPAL_CHECK(near(opal::permittivityFourierComponent(air, planes[0].X) / opal::meanPermittivity(air), 0.0539, 1e-4),
    "silica/air eps_111 / eps_bar");
  // Small x: the series below 0.01 meets the closed form (good to ~1e-12 there).
  for (double x : { 0.0099, 0.0101 })
  {
    const double closed = (std::sin(x) - x * std::cos(x)) / (x * x);
    OPAL_CHECK(near(opal::sphericalBesselJ1(x) / closed, 1.0, 1e-9), "j1 at x = " + std::to_string(x));
  }
  OPAL_CHECK(opal::sphereFormFactor(0.0) == 1.0, "the form factor is 1 at G = 0");
}

void checkSpacings()
{
  const auto planes = opal::fccLatticePlanes(DiameterNm);
  const double expected[] = { DiameterNm * std::sqrt(2.0 / 3.0), DiameterNm / std::sqrt(2.0), DiameterNm / 2.0 };
  for (std::size_t i = 0; i < planes.size(); ++i)
  {
    const std::size_t family = i < 4 ? 0 : i < 7 ? 1 : 2;
    OPAL_CHECK(near(planes[i].SpacingNm, expected[family], 1e-12),
      "plane " + std::to_string(i) + " spacing " + std::to_string(planes[i].SpacingNm));
    OPAL_CHECK(near(glm::length(planes[i].Normal), 1.0, 1e-15), "unit normal " + std::to_string(i));
  }
  OPAL_CHECK(near(planes[0].SpacingNm, opal::fccPlaneSpacing(DiameterNm), 1e-12), "d111 is the paper's eq. 3");
}

// The angles of every family to (111) (planes[0]) among `normals`, and that
// each family's angles come out as docs/design.md §7.1's 70.53, 54.74, 35.26 / 90.
void checkAngles(const std::array<glm::dvec3, opal::FccPlaneCount>& normals, const std::string& frame)
{
  const double a111 = std::acos(1.0 / 3.0) * 180.0 / opal::Pi;          // 70.53
  const double a200 = std::acos(1.0 / std::sqrt(3.0)) * 180.0 / opal::Pi; // 54.74
  const double a220 = std::acos(std::sqrt(2.0 / 3.0)) * 180.0 / opal::Pi; // 35.26
  OPAL_CHECK(near(a111, 70.53, 0.005) && near(a200, 54.74, 0.005) && near(a220, 35.26, 0.005), "the FCC families' angles");
  int at35 = 0, at90 = 0;
  for (std::size_t i = 1; i < normals.size(); ++i)
  {
    const double angle = degreesBetween(normals[0], normals[i]);
    const std::string what = frame + ": plane " + std::to_string(i) + " at " + std::to_string(angle) + " deg to (111)";
    if (i < 4)
    {
      OPAL_CHECK(near(angle, a111, 1e-9), what);
    }
    else if (i < 7)
    {
      OPAL_CHECK(near(angle, a200, 1e-9), what);
    }
    else
    {
      at35 += near(angle, a220, 1e-9) ? 1 : 0;
      at90 += near(angle, 90.0, 1e-9) ? 1 : 0;
    }
  }
  OPAL_CHECK(at35 == 3 && at90 == 3, frame + ": three {220} at 35.26 deg to (111), three at 90");
}

// x' = x cos psi + (n x x) sin psi + n (n . x)(1 - cos psi), Rodrigues' formula.
glm::dvec3 turned(const glm::dvec3& x, const glm::dvec3& n, double psi)
{
  return x * std::cos(psi) + glm::cross(n, x) * std::sin(psi) + n * glm::dot(n, x) * (1.0 - std::cos(psi));
}

void checkOrientation()
{
  const auto planes = opal::fccLatticePlanes(DiameterNm);
  const glm::dvec3 normals[] = { glm::dvec3(1.0) / std::sqrt(3.0), { 0, 1, 0 }, { 0, 0, 1 },
    glm::normalize(glm::dvec3(-0.3, 0.2, 0.9)), glm::normalize(glm::dvec3(0.8, 0.05, -0.6)),
    -glm::dvec3(1.0) / std::sqrt(3.0), glm::normalize(-glm::dvec3(1.0) + glm::dvec3(0, 1e-3, 0)) };
  const double spins[] = { 0.0, 0.7, opal::Pi, -2.0 };
  for (const glm::dvec3& n : normals)
  {
    const auto unspun = opal::modelFrameNormals(planes, opal::latticeOrientation(n, 0.0));
    for (double spin : spins)
    {
      const glm::dquat q = opal::latticeOrientation(n, spin);
      const auto model = opal::modelFrameNormals(planes, q);
      const std::string where = "normal (" + std::to_string(n.x) + ", " + std::to_string(n.y) + ", " +
        std::to_string(n.z) + ") spin " + std::to_string(spin);
      OPAL_CHECK(near(glm::length(q), 1.0, 1e-14), where + ": a unit quaternion");
      OPAL_CHECK(glm::length(model[0] - n) < 1e-12, where + ": [111] stands on the normal");
      for (std::size_t i = 1; i < model.size(); ++i)
      {
        OPAL_CHECK(glm::length(model[i] - turned(unspun[i], n, spin)) < 1e-12,
          where + ": the spin turns plane " + std::to_string(i) + " about the normal");
      }
      checkAngles(model, where);
    }
  }
  const auto identity = opal::modelFrameNormals(planes, opal::latticeOrientation(normals[0], 0.0));
  OPAL_CHECK(glm::length(identity[4] - glm::dvec3(1, 0, 0)) < 1e-15, "n = [111]/sqrt(3), spin 0: the identity");
}

void checkOrders()
{
  const auto planes = opal::fccLatticePlanes(DiameterNm);
  const double n = opal::meanIndex(opal::ColloidalCrystal{}); // lambda_B(111) = 2 d n_bar = 581.9 nm
  OPAL_CHECK(opal::braggOrderCount(planes[0].SpacingNm, n, 1.0, 380.0) == 1, "(111): one order above 380 nm");
  OPAL_CHECK(opal::braggOrderCount(planes[0].SpacingNm, n, 1.0, 250.0) == 2, "(111): two above 250 nm");
  OPAL_CHECK(opal::braggOrderCount(planes[0].SpacingNm, n, 0.5, 250.0) == 1, "(111) at 30 deg: one above 250 nm");
  OPAL_CHECK(opal::braggOrderCount(planes[7].SpacingNm, n, 1.0, 380.0) == 0, "(220): none above 380 nm");
  OPAL_CHECK(opal::braggOrderCount(planes[0].SpacingNm, n, 1.0, 0.0) == 0, "no orders for a bad range");
}

// Coupled-mode theory's two forms as written, for the reflectance's rewrite to hold to.
double designReflectance(double kappa, double delta, double length)
{
  if (std::fabs(delta) < kappa)
  {
    const double s = std::sqrt(kappa * kappa - delta * delta);
    const double sh = std::sinh(s * length), ch = std::cosh(s * length);
    return kappa * kappa * sh * sh / (s * s * ch * ch + delta * delta * sh * sh);
  }
  const double s = std::sqrt(delta * delta - kappa * kappa);
  const double sn = std::sin(s * length);
  return kappa * kappa * sn * sn / (s * s + kappa * kappa * sn * sn);
}

void checkCoupledModeForms()
{
  const double kappa = 1e-4, length = 2e4; // 1/nm, nm: kappa L = 2
  for (double ratio : { 0.0, 0.3, 0.99, 1.01, 1.7, 5.0, 40.0 })
  {
    for (double sign : { 1.0, -1.0 })
    {
      const double delta = sign * ratio * kappa;
      const double r = opal::coupledModeReflectance(kappa, delta, length);
      OPAL_CHECK(near(r, designReflectance(kappa, delta, length), 1e-14),
        "R at delta = " + std::to_string(sign * ratio) + " kappa is coupled-mode theory's form, got " + std::to_string(r));
      OPAL_CHECK(ratio <= 1 || r <= kappa * kappa / (delta * delta - kappa * kappa),
        "off the band R <= kappa^2 / (delta^2 - kappa^2)");
    }
  }
  // The band edge |delta| = kappa: kappa^2 L^2 / (1 + kappa^2 L^2), reached from both sides.
  const double edge = 4.0 / 5.0;
  for (double eps : { 0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6 })
  {
    const double r = opal::coupledModeReflectance(kappa, kappa * (1 + eps), length);
    OPAL_CHECK(near(r, edge, 1e-5), "R near the band edge (" + std::to_string(eps) + ") " + std::to_string(r));
  }
  // Either side of the series' threshold s L = 1e-3, inside (+) and outside (-) the band.
  for (double y : { 1e-3, -1e-3 })
  {
    const auto at = [&](double sl) {
      const double delta = std::sqrt(kappa * kappa - sl * std::fabs(sl) / (length * length));
      return opal::coupledModeReflectance(kappa, delta, length);
    };
    OPAL_CHECK(near(at(0.999 * y), at(1.001 * y), 1e-9) && near(at(y), edge, 1e-6),
      "R is smooth across the series' threshold, s L = " + std::to_string(y));
  }
  OPAL_CHECK(opal::coupledModeReflectance(kappa, 0.0, 1e9) == 1.0, "a deep grating reflects all (no overflow)");
  OPAL_CHECK(opal::coupledModeReflectance(0.0, 0.0, length) == 0.0, "no coupling, no reflection");
  OPAL_CHECK(opal::coupledModeReflectance(kappa, 0.0, 0.0) == 0.0, "no layers, no reflection");
}

opal::CoupledWaveInput silicaInWater(double layers)
{
  const opal::ColloidalCrystal water;
  const auto planes = opal::fccLatticePlanes(DiameterNm);
  opal::CoupledWaveInput in;
  in.SpacingNm = planes[0].SpacingNm;
  in.MeanIndex = opal::meanIndex(water);
  in.FourierComponent = opal::permittivityFourierComponent(water, planes[0].X);
  in.Layers = layers;
  in.WavelengthNm = 2.0 * in.SpacingNm * in.MeanIndex;
  return in;
}

void checkBraggPeak()
{
  for (double layers : { 10.0, 37.5, 100.0, 1000.0 })
  {
    opal::CoupledWaveInput in = silicaInWater(layers);
    const double kappa = opal::Pi * in.FourierComponent / (in.MeanIndex * in.WavelengthNm);
    const double expected = std::tanh(kappa * layers * in.SpacingNm) * std::tanh(kappa * layers * in.SpacingNm);
    const opal::CoupledWaveReflectance r = opal::coupledWaveReflectance(in);
    OPAL_CHECK(near(r.S, expected, 1e-14) && r.P == r.S, "N = " + std::to_string(layers) +
        ": R_s = R_p = tanh^2(kappa L) at the Bragg wavelength, normal incidence: " + std::to_string(r.S));
    in.FourierComponent = -in.FourierComponent;
    OPAL_CHECK(opal::coupledWaveReflectance(in).S == r.S, "the sign of eps_G does not matter");
  }
  // Order 2 of (111), (222): at lambda_B / 2 with eps_222, the same form.
  opal::CoupledWaveInput in = silicaInWater(200.0);
  in.Order = 2;
  in.WavelengthNm /= 2.0;
  in.FourierComponent = opal::permittivityFourierComponent(
    opal::ColloidalCrystal{}, 2.0 * opal::fccLatticePlanes(DiameterNm)[0].X);
  const double kappa2 = opal::Pi * std::fabs(in.FourierComponent) / (in.MeanIndex * in.WavelengthNm);
  const double t = std::tanh(kappa2 * 200.0 * in.SpacingNm);
  OPAL_CHECK(near(opal::coupledWaveReflectance(in).S, t * t, 1e-14), "order 2: tanh^2(kappa_222 N d) at lambda_B / 2");
}

void checkAnglesAndLimits()
{
  opal::CoupledWaveInput in = silicaInWater(50.0);
  const double normalPeak = opal::coupledWaveReflectance(in).S;
  // At 45 deg inside the p fields are perpendicular: |cos 2 theta_n| = 0.
  in.SinGlancing = std::sqrt(0.5);
  in.WavelengthNm = 2.0 * in.SpacingNm * in.MeanIndex * in.SinGlancing;
  const opal::CoupledWaveReflectance at45 = opal::coupledWaveReflectance(in);
  OPAL_CHECK(at45.P < 1e-25 && at45.S > normalPeak, "at 45 deg: no p reflection, s stronger than at normal incidence");
  OPAL_CHECK(near(at45.average(), 0.5 * at45.S, 1e-16), "the average is of s and p");
  // Far off the band (twice lambda_B) almost nothing.
  in = silicaInWater(50.0);
  in.WavelengthNm *= 2.0;
  OPAL_CHECK(opal::coupledWaveReflectance(in).S < 1e-3, "R at 2 lambda_B is small");
  // Grazing, no layers, bad input: 0, never NaN; very many layers: 1 at the peak.
  for (double sinGlancing : { 0.0, 1e-9, -0.5, std::nan("") })
  {
    in = silicaInWater(50.0);
    in.SinGlancing = sinGlancing;
    OPAL_CHECK(opal::coupledWaveReflectance(in).average() == 0.0,
      "grazing: 0, sin theta2 = " + std::to_string(sinGlancing));
  }
  in = silicaInWater(0.0);
  OPAL_CHECK(opal::coupledWaveReflectance(in).average() == 0.0, "no layers: 0");
  in = silicaInWater(1e7);
  OPAL_CHECK(near(opal::coupledWaveReflectance(in).average(), 1.0, 1e-15), "1e7 layers: 1");
  for (double lambda = 300.0; lambda <= 900.0; lambda += 0.25)
  {
    in = silicaInWater(300.0);
    in.SinGlancing = 0.8;
    in.WavelengthNm = lambda;
    const opal::CoupledWaveReflectance r = opal::coupledWaveReflectance(in);
    OPAL_CHECK(r.S >= 0.0 && r.S <= 1.0 && r.P >= 0.0 && r.P <= 1.0, "0 <= R <= 1 at " + std::to_string(lambda));
  }
}
} // namespace

// Each placed domain's lattice orientation (docs/design.md §2.4 step 6) stands
// [111]/sqrt(3) on its drawn normal, spun by its own draw from the LatticeSpin
// stream, for polygons and Voronoi grains; the spins differ between domains.
void checkDomainSpins()
{
  for (opal::DomainLayoutKind kind : { opal::DomainLayoutKind::Polygons, opal::DomainLayoutKind::Voronoi })
  {
    opal::ModelParameters p;
    p.Dimensions = { 40, 20, 50 };
    p.DomainCount = 30;
    p.DomainLayout = kind;
    p.VoronoiCellCount = 80;
    const opal::DomainLayout layout = opal::DomainLayout::build(p);
    double worst = 0.0, smallestGap = 1.0;
    for (const opal::Domain& domain : layout.domains())
    {
      const std::array<double, 4> q = opal::latticeQuaternion(domain);
      const glm::dvec3 n111 = glm::dquat(q[0], q[1], q[2], q[3]) * (glm::dvec3(1.0) / std::sqrt(3.0));
      worst = std::max(worst, glm::length(n111 - glm::dvec3(domain.Normal[0], domain.Normal[1], domain.Normal[2])));
      OPAL_CHECK(domain.LatticeSpin >= 0.0 && domain.LatticeSpin < 2.0 * opal::Pi, "spin within [0, 2 pi)");
      if (domain.Id > 0)
      {
        smallestGap = std::min(smallestGap,
          std::fabs(domain.LatticeSpin - layout.domains()[static_cast<std::size_t>(domain.Id - 1)].LatticeSpin));
      }
    }
    OPAL_CHECK(layout.placedCount() > 1, "the layout places domains");
    OPAL_CHECK(worst < 1e-12, "each orientation takes [111] to the domain's normal");
    OPAL_CHECK(smallestGap > 0.0, "neighbouring domains have their own spins");
  }
}

int TestOpalLatticePlanes(int, char*[])
{
  checkDomainSpins();
  checkFourierRatios();
  checkSpacings();
  checkAngles(opal::modelFrameNormals(opal::fccLatticePlanes(DiameterNm), glm::dquat(1, 0, 0, 0)), "crystal frame");
  checkOrientation();
  checkOrders();
  checkCoupledModeForms();
  checkBraggPeak();
  checkAnglesAndLimits();
  return opaltest::finish("TestOpalLatticePlanes");
}
