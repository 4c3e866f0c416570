#include "OpalReferenceRenderer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace opalreference
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
using glm::dvec3;

// A table of "lambda,v1,v2,..." rows (comments start with '#').
struct Table
{
  std::vector<double> Lambda;
  std::vector<std::vector<double>> Values;

  explicit Table(const std::string& path)
  {
    std::ifstream file(path);
    if (!file)
    {
      throw std::runtime_error("cannot read " + path);
    }
    std::string line;
    while (std::getline(file, line))
    {
      if (line.empty() || line[0] == '#')
        continue;
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream row(line);
      double lambda, v;
      row >> lambda;
      std::vector<double> values;
      while (row >> v)
        values.push_back(v);
      this->Lambda.push_back(lambda);
      this->Values.push_back(values);
    }
  }

  // Linear interpolation; outside the table the end values (hold) or 0.
  double at(std::size_t column, double lambda, bool hold) const
  {
    if (lambda < this->Lambda.front())
      return hold ? this->Values.front()[column] : 0.0;
    if (lambda > this->Lambda.back())
      return hold ? this->Values.back()[column] : 0.0;
    std::size_t i = 1;
    while (i < this->Lambda.size() - 1 && this->Lambda[i] < lambda)
      ++i;
    const double f = (lambda - this->Lambda[i - 1]) / (this->Lambda[i] - this->Lambda[i - 1]);
    return this->Values[i - 1][column] + f * (this->Values[i][column] - this->Values[i - 1][column]);
  }
};

struct Band
{
  double Lambda, Width, D65, X, Y, Z;
};

// Wavelength bins with the tables averaged over each bin (0.1 nm midpoints).
std::vector<Band> wavelengthBands(const View& view, const std::string& cieDirectory)
{
  const Table cmf(cieDirectory + "/cie_1931_2deg_xyz_1nm.csv");
  const Table d65(cieDirectory + "/cie_d65_5nm.csv");
  std::vector<Band> bands;
  for (double lambda = view.LambdaMin; lambda <= view.LambdaMax + 1e-3 * view.LambdaStep; lambda += view.LambdaStep)
  {
    Band band{ lambda, view.LambdaStep, 0, 0, 0, 0 };
    const int n = static_cast<int>(std::ceil(view.LambdaStep / 0.1));
    for (int i = 0; i < n; ++i)
    {
      const double l = lambda - 0.5 * view.LambdaStep + (i + 0.5) * view.LambdaStep / n;
      band.D65 += d65.at(0, l, true) / n;
      band.X += cmf.at(0, l, false) / n;
      band.Y += cmf.at(1, l, false) / n;
      band.Z += cmf.at(2, l, false) / n;
    }
    bands.push_back(band);
  }
  double white = 0;
  for (const Band& b : bands)
    white += b.D65 * b.Y * b.Width;
  for (Band& b : bands)
    b.D65 /= white;
  return bands;
}

class Volume
{
public:
  explicit Volume(const Scene& scene)
    : S(scene)
    , Scattering(scene.Scattering)
    , DomainId(scene.DomainId)
    , Absorption(scene.Absorption)
    , Exponent(scene.AbsorptionExponent)
  {
    this->fillSkin();
  }

  // docs/design.md §3.3: the medium is the smooth surface's inside; a cell
  // whose centre lies outside (within a cell diagonal), with no coefficient
  // of its own, takes those of its inside neighbour (of 26) with the
  // smallest SurfaceDistance.
  void fillSkin()
  {
    const auto& n = this->S.Dimensions;
    const double diagonal = std::sqrt(this->S.Spacing[0] * this->S.Spacing[0] + this->S.Spacing[1] * this->S.Spacing[1] +
      this->S.Spacing[2] * this->S.Spacing[2]);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          const std::size_t v = this->index(i, j, k);
          const double d = this->S.SurfaceDistance[v];
          if (d <= 0 || d > diagonal || this->S.Scattering[v] != 0 || this->S.DomainId[v] >= 0)
            continue;
          std::size_t deepest = v;
          for (int c = std::max(k - 1, 0); c <= std::min(k + 1, n[2] - 1); ++c)
            for (int b = std::max(j - 1, 0); b <= std::min(j + 1, n[1] - 1); ++b)
              for (int a = std::max(i - 1, 0); a <= std::min(i + 1, n[0] - 1); ++a)
              {
                const std::size_t w = this->index(a, b, c);
                if (this->S.SurfaceDistance[w] < this->S.SurfaceDistance[deepest])
                  deepest = w;
              }
          if (this->S.SurfaceDistance[deepest] <= 0)
          {
            this->Scattering[v] = this->S.Scattering[deepest];
            this->DomainId[v] = this->S.DomainId[deepest];
            if (this->absorbs())
            {
              this->Absorption[v] = this->S.Absorption[deepest];
              this->Exponent[v] = this->S.AbsorptionExponent[deepest];
            }
          }
        }
  }

  std::size_t index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
      static_cast<std::size_t>(this->S.Dimensions[0]) *
      (static_cast<std::size_t>(j) + static_cast<std::size_t>(this->S.Dimensions[1]) * static_cast<std::size_t>(k));
  }

  // The voxel whose cell holds p, or false outside the grid.
  bool voxel(const dvec3& p, int c[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      c[a] = static_cast<int>(std::floor((p[a] - this->S.Origin[a]) / this->S.Spacing[a] + 0.5));
      if (c[a] < 0 || c[a] >= this->S.Dimensions[a])
        return false;
    }
    return true;
  }

  double scattering(const dvec3& p) const
  {
    int c[3];
    return this->voxel(p, c) ? this->Scattering[this->index(c[0], c[1], c[2])] : 0.0;
  }

  bool absorbs() const { return !this->Absorption.empty(); }

  // mu_a(lambda) of voxel v (docs/design.md §2.10), 1/mm.
  double absorption(std::size_t v, double lambda) const
  {
    return this->absorbs() ? this->Absorption[v] * std::pow(550.0 / lambda, static_cast<double>(this->Exponent[v])) : 0.0;
  }

  double absorption(const dvec3& p, double lambda) const
  {
    int c[3];
    return this->voxel(p, c) ? this->absorption(this->index(c[0], c[1], c[2]), lambda) : 0.0;
  }

  // True if voxel v scatters or absorbs (a domain voxel of the paper does neither).
  bool extinguishes(std::size_t v) const
  {
    return this->Scattering[v] > 0 || (this->absorbs() && this->Absorption[v] > 0);
  }

  // Trilinear SurfaceDistance between voxel centres; from the outermost
  // centres to the grid's box (half a cell) the outermost cells' interpolant
  // continued linearly, beyond the box the distance to it added. (Clamping at
  // the outermost centres instead cut a chamfer under the rim where the dome
  // meets the base y = 0: docs/design.md §3.3.)
  double distance(const dvec3& p) const
  {
    double g[3];
    int c0[3], c1[3];
    dvec3 nearest(0.0);
    for (int a = 0; a < 3; ++a)
    {
      const double lo = this->S.Origin[a] - 0.5 * this->S.Spacing[a];
      const double hi = lo + this->S.Dimensions[a] * this->S.Spacing[a];
      nearest[a] = std::min(std::max(p[a], lo), hi);
      g[a] = (nearest[a] - this->S.Origin[a]) / this->S.Spacing[a];
      c0[a] = std::max(std::min(static_cast<int>(std::floor(g[a])), this->S.Dimensions[a] - 2), 0);
      c1[a] = std::min(c0[a] + 1, this->S.Dimensions[a] - 1);
      g[a] -= c0[a];
    }
    double value = 0;
    for (int corner = 0; corner < 8; ++corner)
    {
      const int i = (corner & 1) ? c1[0] : c0[0], j = (corner & 2) ? c1[1] : c0[1], k = (corner & 4) ? c1[2] : c0[2];
      const double w = ((corner & 1) ? g[0] : 1 - g[0]) * ((corner & 2) ? g[1] : 1 - g[1]) * ((corner & 4) ? g[2] : 1 - g[2]);
      value += w * this->S.SurfaceDistance[this->index(i, j, k)];
    }
    return value + glm::length(p - nearest);
  }

  dvec3 normal(const dvec3& p) const
  {
    const dvec3 h(this->S.Spacing[0], this->S.Spacing[1], this->S.Spacing[2]);
    const dvec3 g((this->distance(p + dvec3(h.x, 0, 0)) - this->distance(p - dvec3(h.x, 0, 0))) / (2 * h.x),
      (this->distance(p + dvec3(0, h.y, 0)) - this->distance(p - dvec3(0, h.y, 0))) / (2 * h.y),
      (this->distance(p + dvec3(0, 0, h.z)) - this->distance(p - dvec3(0, 0, h.z))) / (2 * h.z));
    return glm::length(g) > 0 ? glm::normalize(g) : dvec3(0, 1, 0);
  }

  // The grid's box hit by a ray: [tNear, tFar], empty if tNear > tFar.
  std::array<double, 2> box(const dvec3& o, const dvec3& d) const
  {
    double tNear = 0, tFar = 1e300;
    for (int a = 0; a < 3; ++a)
    {
      const double lo = this->S.Origin[a] - 0.5 * this->S.Spacing[a];
      const double hi = lo + this->S.Dimensions[a] * this->S.Spacing[a];
      const double t0 = (lo - o[a]) / d[a], t1 = (hi - o[a]) / d[a];
      tNear = std::max(tNear, std::min(t0, t1));
      tFar = std::min(tFar, std::max(t0, t1));
    }
    return { tNear, tFar };
  }

  // Where a ray first crosses into the opal (small fixed steps, then bisection), or -1.
  // From tFrom on where that point lies outside (a neighbouring ray's hit less a margin).
  double entry(const dvec3& o, const dvec3& d, double tFrom = 0) const
  {
    auto [t0, t1] = this->box(o, d);
    if (tFrom > t0 && this->distance(o + tFrom * d) > 0)
      t0 = tFrom;
    const double step = 0.02 * this->minSpacing();
    for (double t = t0; t <= t1; t += step)
    {
      if (this->distance(o + t * d) <= 0)
        return this->bisect(o, d, t - step, t, true);
    }
    return -1;
  }

  // Root of SurfaceDistance along the ray in [a, b]; `inward` if it goes from + to -.
  double bisect(const dvec3& o, const dvec3& d, double a, double b, bool inward) const
  {
    for (int i = 0; i < 50; ++i)
    {
      const double m = 0.5 * (a + b);
      const bool outside = this->distance(o + m * d) > 0;
      (outside == inward ? a : b) = m;
    }
    return inward ? b : a;
  }

  double minSpacing() const { return std::min({ this->S.Spacing[0], this->S.Spacing[1], this->S.Spacing[2] }); }

  const Scene& S;
  std::vector<float> Scattering; // the scene's, with the skin filled
  std::vector<int> DomainId;
  std::vector<float> Absorption, Exponent; // likewise; empty without absorption
};

// Absorption depths along a path at 550 nm, by exponent p: a voxel's
// mu_a(550) times its length goes to its exponent's depth, so any mix of
// exponents gives exact depths at every wavelength.
using AbsorptionDepth = std::map<float, double>;

double atWavelength(const AbsorptionDepth& depth, double lambda)
{
  double tau = 0;
  for (const auto& [exponent, depth550] : depth)
    tau += depth550 * std::pow(550.0 / lambda, static_cast<double>(exponent));
  return tau;
}

double fresnel(double cosI, double mu)
{
  const double c = std::min(std::max(cosI, 0.0), 1.0);
  const double sinT2 = (1 - c * c) / (mu * mu);
  if (sinT2 >= 1)
    return 1;
  const double cosT = std::sqrt(1 - sinT2);
  const double rs = (c - mu * cosT) / (c + mu * cosT), rp = (mu * c - cosT) / (mu * c + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// Light reaching p (eq. 6, 7 with docs/design.md §4.1's 1/r^2 to the sample), at the
// wavelength lambda (rayleigh = (550/lambda)^4) optical depth tau (scattering and absorption)
// and geometric factor g: march towards the light one voxel
// length at a time, nearest-voxel coefficients at each step's midpoint, until
// the path leaves the opal at L_in, where the Fresnel transmission applies.
void lightAt(const Volume& v, const dvec3& p, const dvec3& light, double apexDistance2, double mu, double rayleigh,
  double lambda, double& tau, double& g)
{
  auto extinction = [&](const dvec3& at) { return v.scattering(at) * rayleigh + v.absorption(at, lambda); };
  const dvec3 d = glm::normalize(light - p);
  const double h = v.minSpacing();
  const double tEnd = std::min(v.box(p, d)[1], glm::length(light - p));
  tau = 0;
  double t = 0, exit = tEnd;
  while (t < tEnd)
  {
    const double step = std::min(h, tEnd - t);
    if (v.distance(p + (t + step) * d) > 0)
    {
      exit = v.bisect(p, d, t, t + step, false);
      tau += extinction(p + 0.5 * (t + exit) * d) * (exit - t);
      break;
    }
    tau += extinction(p + (t + 0.5 * step) * d) * step;
    t += step;
  }
  const dvec3 entry = p + exit * d;
  const double r2 = glm::dot(light - p, light - p);
  g = (1 - fresnel(glm::dot(v.normal(entry), d), mu)) * apexDistance2 / r2;
}

// --- Converged mode: the light exactly, the view path refined ---

// The pieces of [a, b] of p + t d in the piecewise-constant fields,
// exactly: every grid plane between voxel cells that the segment crosses,
// listed and sorted; each piece's midpoint names its voxel. Calls
// piece(midpoint, length) for each.
template <typename Piece>
void forEachPiece(const Volume& v, const dvec3& p, const dvec3& d, double a, double b, Piece&& piece)
{
  std::vector<double> cuts{ a, b };
  for (int k = 0; k < 3; ++k)
  {
    if (d[k] == 0)
      continue;
    const double spacing = v.S.Spacing[k], first = v.S.Origin[k] + 0.5 * spacing;
    const double lo = std::min(p[k] + a * d[k], p[k] + b * d[k]), hi = std::max(p[k] + a * d[k], p[k] + b * d[k]);
    for (double i = std::ceil((lo - first) / spacing); first + i * spacing <= hi; ++i)
      cuts.push_back((first + i * spacing - p[k]) / d[k]);
  }
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t i = 1; i < cuts.size(); ++i)
  {
    const double t0 = std::max(cuts[i - 1], a), t1 = std::min(cuts[i], b);
    if (t1 > t0)
      piece(p + 0.5 * (t0 + t1) * d, t1 - t0);
  }
}

// The scattering optical depth at 550 nm over [a, b] of p + t d, exactly,
// and the absorption depths by exponent added to `absorption`.
double exactDepth(const Volume& v, const dvec3& p, const dvec3& d, double a, double b, AbsorptionDepth& absorption)
{
  double tau = 0;
  forEachPiece(v, p, d, a, b, [&](const dvec3& middle, double length) {
    tau += v.scattering(middle) * length;
    int c[3];
    if (v.absorbs() && v.voxel(middle, c))
    {
      const std::size_t voxel = v.index(c[0], c[1], c[2]);
      absorption[v.Exponent[voxel]] += v.Absorption[voxel] * length;
    }
  });
  return tau;
}

// The stretches of p + t d, 0 <= t <= tEnd, inside the smooth surface:
// scanned in half-voxel steps, each end bisected.
std::vector<std::array<double, 2>> insideStretches(const Volume& v, const dvec3& p, const dvec3& d, double tEnd)
{
  std::vector<std::array<double, 2>> stretches;
  const double step = 0.5 * v.minSpacing();
  bool inside = v.distance(p) <= 0;
  double start = 0;
  for (double t = step; inside || t - step < tEnd; t += step)
  {
    const double at = std::min(t, tEnd);
    const bool now = v.distance(p + at * d) <= 0;
    if (now != inside)
    {
      const double edge = v.bisect(p, d, at - step, at, !inside);
      if (inside)
        stretches.push_back({ start, edge });
      start = edge;
      inside = now;
    }
    if (at >= tEnd)
    {
      if (inside)
        stretches.push_back({ start, tEnd });
      break;
    }
  }
  return stretches;
}

// The light at p exactly (converged mode): the optical depth of every
// stretch of the straight path inside the opal, each exact; the light
// enters where the stretch nearest it ends (L_in).
void lightExact(const Volume& v, const dvec3& p, const dvec3& light, double apexDistance2, double mu, double& tau,
  AbsorptionDepth& absorption, double& g)
{
  const dvec3 d = glm::normalize(light - p);
  const double tEnd = std::min(v.box(p, d)[1], glm::length(light - p));
  tau = 0;
  dvec3 entry = p;
  for (const auto& stretch : insideStretches(v, p, d, tEnd))
  {
    tau += exactDepth(v, p, d, stretch[0], stretch[1], absorption);
    entry = p + stretch[1] * d;
  }
  g = (1 - fresnel(glm::dot(v.normal(entry), d), mu)) * apexDistance2 / glm::dot(light - p, light - p);
}

// --- Camera, surface and view path ---

struct Camera
{
  explicit Camera(const View& view)
    : Eye(view.Eye[0], view.Eye[1], view.Eye[2])
    , Forward(glm::normalize(dvec3(view.FocalPoint[0], view.FocalPoint[1], view.FocalPoint[2]) - Eye))
    , Right(glm::normalize(glm::cross(Forward, dvec3(view.ViewUp[0], view.ViewUp[1], view.ViewUp[2]))))
    , Up(glm::cross(Right, Forward))
    , TanHalf(std::tan(view.ViewAngle * Pi / 360.0))
    , Aspect(static_cast<double>(view.Width) / view.Height)
    , Width(view.Width)
    , Height(view.Height)
  {
  }

  // The ray through image point (x, y), in pixels from the top left.
  dvec3 direction(double x, double y) const
  {
    const double nx = 2 * x / this->Width - 1, ny = 1 - 2 * y / this->Height;
    return glm::normalize(this->Forward + nx * this->TanHalf * this->Aspect * this->Right + ny * this->TanHalf * this->Up);
  }

  dvec3 Eye, Forward, Right, Up;
  double TanHalf, Aspect;
  int Width, Height;
};

// |L - apex|^2: irradiance 1 at the apex, the top of the surface over the grid's centre column.
double apexDistanceSquared(const Volume& volume, const dvec3& light)
{
  const Scene& scene = volume.S;
  const int ci = scene.Dimensions[0] / 2, ck = scene.Dimensions[2] / 2;
  const dvec3 column(scene.Origin[0] + ci * scene.Spacing[0], 0, scene.Origin[2] + ck * scene.Spacing[2]);
  const double top = scene.Origin[1] + (scene.Dimensions[1] - 1) * scene.Spacing[1];
  dvec3 apex(column.x, top + 0.5 * scene.Spacing[1], column.z);
  for (int j = scene.Dimensions[1] - 1; j >= 0; --j)
  {
    const double y = scene.Origin[1] + j * scene.Spacing[1];
    if (volume.distance(dvec3(column.x, y, column.z)) <= 0)
    {
      const double above = std::min(y + scene.Spacing[1], top + scene.Spacing[1]);
      apex.y = volume.bisect(dvec3(column.x, 0, column.z), dvec3(0, 1, 0), y, above, false);
      break;
    }
  }
  return glm::dot(light - apex, light - apex);
}

// The mirror image of the primary ray through image point (x, y): where it
// passes closest to the light, and the cosine of incidence.
struct MirrorRay
{
  bool Hit = false;
  dvec3 Near{ 0.0 };
  double CosIncidence = 0;
};

MirrorRay mirrorRay(const Volume& volume, const Camera& camera, const dvec3& light, double x, double y, double tFrom)
{
  MirrorRay ray;
  const dvec3 d = camera.direction(x, y);
  const double t = volume.entry(camera.Eye, d, tFrom);
  if (t < 0)
    return ray;
  const dvec3 p = camera.Eye + t * d, n = volume.normal(p), mirrored = glm::reflect(d, n);
  ray.Hit = -glm::dot(d, n) > 0;
  ray.Near = p + std::max(glm::dot(light - p, mirrored), 0.0) * mirrored;
  ray.CosIncidence = -glm::dot(d, n);
  return ray;
}

// The light's Fresnel highlight at a pixel: over s x s sub-rays, the
// fraction whose mirror ray meets the light's sphere, each weighted by F.
double highlightCoverage(const Volume& volume, const Camera& camera, const View& view, int px, int py, int s)
{
  const dvec3 light(view.Light[0], view.Light[1], view.Light[2]);
  double highlight = 0;
  for (int sy = 0; sy < s; ++sy)
    for (int sx = 0; sx < s; ++sx)
    {
      const MirrorRay ray = mirrorRay(volume, camera, light, px + (sx + 0.5) / s, py + (sy + 0.5) / s, 0.0);
      if (ray.Hit && glm::length(ray.Near - light) <= view.LightRadius)
        highlight += fresnel(ray.CosIncidence, view.RefractiveIndex) / (s * s);
    }
  return highlight;
}

// The highlight over the image square [x, x + size]^2, as a share of it
// (converged mode): whole where the mirror rays of its corners and centre
// all pass inside the light's disc (or those that meet the opal all
// outside it) by more than their spread, else split in four, `depth` levels
// down, the leaves point-sampled; each part weighted by its Fresnel
// reflectance.
double adaptiveHighlight(const Volume& volume, const Camera& camera, const View& view, double x, double y, double size,
  int depth, double tFrom)
{
  const dvec3 light(view.Light[0], view.Light[1], view.Light[2]);
  const double r = view.LightRadius;
  const MirrorRay centre = mirrorRay(volume, camera, light, x + 0.5 * size, y + 0.5 * size, tFrom);
  std::vector<MirrorRay> rays{ centre };
  for (const auto& corner : { glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1) })
    rays.push_back(mirrorRay(volume, camera, light, x + corner.x * size, y + corner.y * size, tFrom));
  // Over the rays that meet the opal: how near and far they pass the light, and their spread.
  bool allHit = true, anyHit = false;
  double nearest = 1e300, farthest = 0, spread = 0;
  for (const MirrorRay& ray : rays)
  {
    allHit = allHit && ray.Hit;
    if (!ray.Hit)
      continue;
    anyHit = true;
    nearest = std::min(nearest, glm::length(ray.Near - light));
    farthest = std::max(farthest, glm::length(ray.Near - light));
    for (const MirrorRay& other : rays)
      spread = other.Hit ? std::max(spread, glm::length(ray.Near - other.Near)) : spread;
  }
  const double reflectance = centre.Hit ? fresnel(centre.CosIncidence, view.RefractiveIndex) : 0.0;
  if (!anyHit || nearest > r + spread)
    return 0.0;
  if (allHit && farthest < r - spread)
    return reflectance;
  if (depth == 0)
    return centre.Hit && glm::length(centre.Near - light) <= r ? reflectance : 0.0;
  double sum = 0;
  for (const auto& quarter : { glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1) })
    sum += 0.25 * adaptiveHighlight(volume, camera, view, x + quarter.x * 0.5 * size, y + quarter.y * 0.5 * size,
      0.5 * size, depth - 1, tFrom);
  return sum;
}

// A pixel's highlight: SpecularSamples x SpecularSamples sub-rays, or in
// converged mode the adaptive subdivision.
double pixelHighlight(const Volume& volume, const Camera& camera, const View& view, int px, int py)
{
  if (!view.Converged)
    return highlightCoverage(volume, camera, view, px, py, view.SpecularSamples);
  // Rays within the pixel meet the surface near its centre's: search from a little before.
  const double tCentre = volume.entry(camera.Eye, camera.direction(px + 0.5, py + 0.5));
  return adaptiveHighlight(volume, camera, view, px, py, 1.0, view.ConvergedHighlightDepth,
    tCentre < 0 ? 0.0 : tCentre - 2 * volume.minSpacing());
}

// Calls shade(pixel) for every pixel, interleaved over the machine's cores
// (pixels are independent; each writes only its own outputs).
template <typename Shade>
void forEachPixel(std::size_t pixels, Shade&& shade)
{
  const std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> workers;
  for (std::size_t t = 0; t < threads; ++t)
    workers.emplace_back([&, t] {
      for (std::size_t pixel = t; pixel < pixels; pixel += threads)
        shade(pixel);
    });
  for (std::thread& worker : workers)
    worker.join();
}

// Every pixel's highlight.
std::vector<double> highlights(const Volume& volume, const View& view)
{
  const Camera camera(view);
  std::vector<double> result(static_cast<std::size_t>(view.Width) * view.Height, 0.0);
  forEachPixel(result.size(), [&](std::size_t pixel) {
    result[pixel] = pixelHighlight(volume, camera, view, static_cast<int>(pixel % view.Width), static_cast<int>(pixel / view.Width));
  });
  return result;
}

// The exact voxel-by-voxel segments of the refracted ray from `origin` to tExit.
struct Segment
{
  double T0, T1;
  int Voxel;
};

std::vector<Segment> viewSegments(const Volume& volume, const dvec3& origin, const dvec3& inward, double tExit)
{
  const Scene& scene = volume.S;
  std::vector<Segment> segments;
  int c[3];
  volume.voxel(origin, c);
  double t = 0;
  while (t < tExit)
  {
    // The nearest cell boundary ahead and its axis.
    double next = tExit;
    int axis = -1;
    for (int a = 0; a < 3; ++a)
    {
      if (inward[a] == 0)
        continue;
      const double boundary = scene.Origin[a] + (c[a] + (inward[a] > 0 ? 0.5 : -0.5)) * scene.Spacing[a];
      const double tb = (boundary - origin[a]) / inward[a];
      if (tb < next)
      {
        next = tb;
        axis = a;
      }
    }
    next = std::max(next, t);
    const bool inside = c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < scene.Dimensions[0] &&
      c[1] < scene.Dimensions[1] && c[2] < scene.Dimensions[2];
    if (next > t && inside)
      segments.push_back({ t, next, static_cast<int>(volume.index(c[0], c[1], c[2])) });
    if (axis < 0)
      break;
    c[axis] += inward[axis] > 0 ? 1 : -1;
    t = next;
  }
  return segments;
}

// What the view ray samples: a domain once at its segment's middle (a new
// crossing only where the previous segment was not the same domain), the
// body in `substeps` equal pieces of each segment.
struct Sample
{
  dvec3 Middle;
  double Length;
  int Voxel;
  int Domain; // -1 for the body
  double Tau = 0, G = 0; // the light, where computed ahead (converged mode)
  AbsorptionDepth TauAbsorption; // likewise, the light's absorption depths
};

std::vector<Sample> viewSamples(const Volume& volume, const std::vector<Segment>& segments, const dvec3& origin,
  const dvec3& inward, int substeps)
{
  std::vector<Sample> samples;
  int lastDomain = -1;
  for (const Segment& segment : segments)
  {
    const int domain = volume.DomainId[static_cast<std::size_t>(segment.Voxel)];
    if (domain >= 0)
    {
      if (domain != lastDomain)
        samples.push_back(
          { origin + 0.5 * (segment.T0 + segment.T1) * inward, segment.T1 - segment.T0, segment.Voxel, domain, 0, 0, {} });
      lastDomain = domain;
      // The paper's domains neither scatter nor absorb; beyond it (docs/design.md §2.10) they may.
      if (!volume.extinguishes(static_cast<std::size_t>(segment.Voxel)))
        continue;
    }
    else
      lastDomain = -1;
    const double length = (segment.T1 - segment.T0) / substeps;
    for (int q = 0; q < substeps; ++q)
      samples.push_back({ origin + (segment.T0 + (q + 0.5) * length) * inward, length, segment.Voxel, -1, 0, 0, {} });
  }
  return samples;
}

// --- The pixel ---

struct PixelResult
{
  std::array<double, 3> XYZ{};
  double Dominant = 0;
};

// What a render shares over its pixels.
struct Setup
{
  const Volume& V;
  const View& ViewSettings;
  const std::vector<Band>& Bands;
  dvec3 Light;
  double ApexDistance2;
  int Substeps;
};

// The light of a sample at the wavelength lambda (rayleigh = (550/lambda)^4):
// its optical depth and geometry factor, computed ahead in converged mode; in
// the literal mode marched again for every wavelength, as the paper does.
void sampleLight(const Setup& s, const Sample& sample, double rayleigh, double lambda, double& tau, double& g)
{
  if (s.ViewSettings.Converged)
  {
    tau = sample.Tau * rayleigh + atWavelength(sample.TauAbsorption, lambda);
    g = sample.G;
    return;
  }
  lightAt(s.V, sample.Middle, s.Light, s.ApexDistance2, s.ViewSettings.RefractiveIndex, rayleigh, lambda, tau, g);
}

// Bragg-Snell (eq. 4, 9) at a domain crossing: the box band averaged over this bin.
double diffracted(const Setup& s, const Sample& sample, const Band& band, double rayleigh, double tauView, double& lambdaB)
{
  const auto& lattice = s.V.S.Domains[static_cast<std::size_t>(sample.Domain)];
  const dvec3 normal(lattice[0], lattice[1], lattice[2]);
  const double mu = s.ViewSettings.RefractiveIndex, width = s.ViewSettings.BraggBandwidth;
  const double sinGlancing = std::fabs(glm::dot(glm::normalize(s.Light - sample.Middle), normal));
  lambdaB = 2 * lattice[3] * std::sqrt(std::max(mu * mu - (1 - sinGlancing * sinGlancing), 0.0));
  const double lo = std::max(band.Lambda - 0.5 * band.Width, lambdaB * (1 - 0.5 * width));
  const double hi = std::min(band.Lambda + 0.5 * band.Width, lambdaB * (1 + 0.5 * width));
  const double b = std::max(hi - lo, 0.0) / band.Width;
  double tau, g;
  sampleLight(s, sample, rayleigh, band.Lambda, tau, g);
  return s.ViewSettings.DiffractionGain * b * g * std::exp(-(tau + tauView)) / Pi;
}

// Every wavelength separately (the paper's cost): the body's single
// scattering (eq. 8, phase 1/(4 pi), T_V at each sample's middle) and the
// domains' diffraction, extinction mu_s + mu_a on both paths (tauView: at
// this wavelength); the ray's XYZ (transmitted: the 1 - F it carries in)
// and its dominant Bragg wavelength.
PixelResult shadePixel(const Setup& s, const std::vector<Sample>& samples, double transmitted)
{
  PixelResult pixel;
  std::vector<double> crossingY, crossingLambda;
  for (const Band& band : s.Bands)
  {
    const double rayleigh = std::pow(550.0 / band.Lambda, 4.0);
    double radiance = 0, tauView = 0;
    std::size_t crossing = 0;
    for (const Sample& sample : samples)
    {
      const auto voxel = static_cast<std::size_t>(sample.Voxel);
      const double mus = s.V.Scattering[voxel] * rayleigh, mua = s.V.absorption(voxel, band.Lambda);
      if (sample.Domain >= 0)
      {
        // Seen at the middle of the crossing's first voxel.
        double lambdaB;
        const double value = diffracted(s, sample, band, rayleigh, tauView + 0.5 * (mus + mua) * sample.Length, lambdaB);
        radiance += value;
        if (crossingY.size() <= crossing)
        {
          crossingY.push_back(0);
          crossingLambda.push_back(lambdaB);
        }
        crossingY[crossing++] += value * band.D65 * band.Y * band.Width;
        continue;
      }
      if (mus > 0)
      {
        double tau, g;
        sampleLight(s, sample, rayleigh, band.Lambda, tau, g);
        radiance += g * std::exp(-tau) * mus / (4 * Pi) * sample.Length *
          std::exp(-(tauView + 0.5 * (mus + mua) * sample.Length));
      }
      tauView += (mus + mua) * sample.Length;
    }
    const double total = transmitted * radiance * band.D65;
    pixel.XYZ[0] += total * band.X * band.Width;
    pixel.XYZ[1] += total * band.Y * band.Width;
    pixel.XYZ[2] += total * band.Z * band.Width;
  }
  // The dominant Bragg wavelength: the crossing whose light has the most luminance.
  const auto brightest = std::max_element(crossingY.begin(), crossingY.end());
  if (brightest != crossingY.end() && *brightest > 0)
    pixel.Dominant = crossingLambda[static_cast<std::size_t>(brightest - crossingY.begin())];
  return pixel;
}

// Where the refracted ray from `origin` leaves the opal: fine steps, then bisection.
double viewExit(const Volume& volume, const dvec3& origin, const dvec3& inward)
{
  const double h = volume.minSpacing();
  const double tBox = volume.box(origin, inward)[1];
  for (double t = 0; t < tBox; t += 0.02 * h)
  {
    if (volume.distance(origin + t * inward) > 0)
      return volume.bisect(origin, inward, std::max(0.0, t - 0.02 * h), t, false);
  }
  return tBox;
}

// A ray through image point (x, y), in pixels from the top left: whether it
// meets the opal, its cosine of incidence, the first domain its refracted ray
// crosses (-1: none) and, if shaded, its body's XYZ and dominant Bragg
// wavelength (the highlight apart: a pixel's is integrated on its own).
struct RaySample
{
  bool Hit = false;
  int FirstDomain = -1;
  double CosIncidence = 0;
  PixelResult Body;
};

RaySample traceRay(const Setup& s, const Camera& camera, double x, double y, int substeps, bool shade)
{
  RaySample ray;
  const Volume& volume = s.V;
  const View& view = s.ViewSettings;
  const dvec3 d = camera.direction(x, y);
  const double tHit = volume.entry(camera.Eye, d);
  if (tHit < 0)
    return ray;
  ray.Hit = true;
  const dvec3 hit = camera.Eye + tHit * d;
  const dvec3 n = volume.normal(hit);
  ray.CosIncidence = -glm::dot(d, n);
  // The refracted ray, from just inside the surface to where it leaves.
  const dvec3 inward = glm::refract(d, n, 1.0 / view.RefractiveIndex);
  const dvec3 origin = hit - 1e-4 * volume.minSpacing() * n;
  std::vector<Sample> samples =
    viewSamples(volume, viewSegments(volume, origin, inward, viewExit(volume, origin, inward)), origin, inward, substeps);
  const auto domain = std::find_if(samples.begin(), samples.end(), [](const Sample& a) { return a.Domain >= 0; });
  ray.FirstDomain = domain == samples.end() ? -1 : domain->Domain;
  if (!shade)
    return ray;
  if (view.Converged)
    for (Sample& sample : samples)
      lightExact(volume, sample.Middle, s.Light, s.ApexDistance2, view.RefractiveIndex, sample.Tau, sample.TauAbsorption,
        sample.G);
  ray.Body = shadePixel(s, samples, 1 - fresnel(ray.CosIncidence, view.RefractiveIndex));
  return ray;
}

// The XYZ of a pixel's highlight (its share times F, the light's radiance, D65).
std::array<double, 3> highlightXYZ(const Setup& s, double highlight)
{
  const View& view = s.ViewSettings;
  const double lightRadiance = s.ApexDistance2 / (Pi * view.LightRadius * view.LightRadius);
  std::array<double, 3> xyz{};
  for (const Band& band : s.Bands)
  {
    const double total = highlight * lightRadiance * band.D65 * band.Width;
    xyz[0] += total * band.X;
    xyz[1] += total * band.Y;
    xyz[2] += total * band.Z;
  }
  return xyz;
}

// One render of the pixels' centre rays with s.Substeps body samples per
// voxel segment, and each centre ray's first domain.
struct CentreRender
{
  Image Picture;
  std::vector<int> FirstDomain;
};

CentreRender renderOnce(const Setup& s, const std::vector<double>& highlight)
{
  const View& view = s.ViewSettings;
  const Camera camera(view);
  CentreRender render;
  Image& image = render.Picture;
  const std::size_t pixels = static_cast<std::size_t>(view.Width) * view.Height;
  image.XYZ.assign(3 * pixels, 0.0);
  image.Dominant.assign(pixels, 0.0);
  image.Hit.assign(pixels, 0);
  image.CosIncidence.assign(pixels, 0.0);
  image.Highlight = highlight;
  image.Refined.assign(pixels, 0);
  image.ViewSubsteps = s.Substeps;
  render.FirstDomain.assign(pixels, -1);
  forEachPixel(pixels, [&](std::size_t pixel) {
    const RaySample ray = traceRay(s, camera, static_cast<double>(pixel % view.Width) + 0.5,
      static_cast<double>(pixel / view.Width) + 0.5, s.Substeps, true);
    const std::array<double, 3> shine = highlightXYZ(s, highlight[pixel]);
    for (std::size_t c = 0; c < 3; ++c)
      image.XYZ[3 * pixel + c] = ray.Body.XYZ[c] + shine[c];
    image.Hit[pixel] = ray.Hit ? 1 : 0;
    image.CosIncidence[pixel] = ray.CosIncidence;
    image.Dominant[pixel] = ray.Body.Dominant;
    render.FirstDomain[pixel] = ray.FirstDomain;
  });
  return render;
}

// 5% of an image's mean luminance: below it a pixel's relative difference says little.
double darkFloor(const Image& image)
{
  double meanY = 0;
  for (std::size_t p = 0; p < image.Hit.size(); ++p)
    meanY += image.XYZ[3 * p + 1] / static_cast<double>(image.Hit.size());
  return 0.05 * meanY;
}

// The largest change of any pixel's XYZ component between two renders,
// relative to the pixel (or darkFloor, where darker).
double largestChange(const Image& a, const Image& b)
{
  const double floor = darkFloor(b);
  double change = 0;
  for (std::size_t i = 0; i < b.XYZ.size(); ++i)
    change = std::max(change, std::fabs(a.XYZ[i] - b.XYZ[i]) / std::max(std::fabs(b.XYZ[i]), floor));
  return change;
}

// --- The pixel's area (converged mode) ---

// What the area pass shares: the setup, the substeps its rays take, the
// tolerance's scale (darkFloor) and the camera.
struct AreaSetup
{
  const Setup& S;
  int Substeps;
  double Floor;
  Camera Eye;
};

// The rays of a square of the image: its four corners (top left, top right,
// bottom left, bottom right) and its centre.
struct SquareRays
{
  std::array<RaySample, 4> Corner;
  RaySample Centre;
};

bool sameGeometry(const SquareRays& q)
{
  return std::all_of(q.Corner.begin(), q.Corner.end(), [&](const RaySample& r) {
    return r.Hit == q.Centre.Hit && r.FirstDomain == q.Centre.FirstDomain;
  });
}

// The square's mean by the five-point rule (2 centre + mean of corners) / 3,
// exact for a quadratic, and whether the rule holds there: the square's rays
// see the same surface and first domain, and the rule moves the centre's
// value, weighted by the square's share of the pixel (`area`), by at most
// RuleTrust tolerances of the pixel's scale, per XYZ component. The centre's
// error is of order h^2 and the rule's h^4, so where the centre errs by a
// few tolerances the rule errs by far less than one.
constexpr double RuleTrust = 8;

std::array<double, 3> fivePointMean(const SquareRays& q)
{
  std::array<double, 3> mean{};
  for (std::size_t c = 0; c < 3; ++c)
  {
    double corners = 0;
    for (const RaySample& r : q.Corner)
      corners += 0.25 * r.Body.XYZ[c];
    mean[c] = (2 * q.Centre.Body.XYZ[c] + corners) / 3;
  }
  return mean;
}

bool smoothSquare(const SquareRays& q, const std::array<double, 3>& mean, double area, double scale, double tolerance)
{
  if (!sameGeometry(q))
    return false;
  for (std::size_t c = 0; c < 3; ++c)
    if (area * std::fabs(mean[c] - q.Centre.Body.XYZ[c]) > RuleTrust * tolerance * scale)
      return false;
  return true;
}

// The mean over the square [x, x + size]^2 with these rays: the five-point
// rule where smooth or `depth` levels down, else the mean of its four
// quarters (eight new rays: the edges' midpoints and the quarters' centres).
std::array<double, 3> squareMean(const AreaSetup& a, double x, double y, double size, const SquareRays& q, int depth,
  double scale)
{
  const std::array<double, 3> mean = fivePointMean(q);
  if (depth == 0 || smoothSquare(q, mean, size * size, scale, a.S.ViewSettings.ConvergenceTolerance))
    return mean;
  const double h = 0.5 * size;
  auto ray = [&](double u, double v) { return traceRay(a.S, a.Eye, x + u * size, y + v * size, a.Substeps, true); };
  const RaySample top = ray(0.5, 0), left = ray(0, 0.5), right = ray(1, 0.5), bottom = ray(0.5, 1);
  const std::array<SquareRays, 4> quarters{ SquareRays{ { q.Corner[0], top, left, q.Centre }, ray(0.25, 0.25) },
    SquareRays{ { top, q.Corner[1], q.Centre, right }, ray(0.75, 0.25) },
    SquareRays{ { left, q.Centre, q.Corner[2], bottom }, ray(0.25, 0.75) },
    SquareRays{ { q.Centre, right, bottom, q.Corner[3] }, ray(0.75, 0.75) } };
  std::array<double, 3> sum{};
  for (std::size_t i = 0; i < 4; ++i)
  {
    const std::array<double, 3> part =
      squareMean(a, x + h * static_cast<double>(i % 2), y + h * static_cast<double>(i / 2), h, quarters[i], depth - 1, scale);
    for (std::size_t c = 0; c < 3; ++c)
      sum[c] += 0.25 * part[c];
  }
  return sum;
}

// Converged mode: each pixel's mean over its area (a box filter), from its
// corners' rays and its centre's at `coarse`'s substeps (one body sample per
// voxel segment, which keeps the pass at ~15% of the render): where the
// five-point rule holds (smoothSquare), the pixel is its converged centre
// value plus the rule's correction; elsewhere (the silhouette, a domain's
// edge, a steep change) the pixel is split adaptively (squareMean,
// View::AreaDepth levels) and the centre's value corrected by the split's
// mean less the centre. Both corrections are differences of rays at the
// coarse substeps, whose quadrature error, common to both, cancels (fig15's
// terminator: within 0.17% of the same pass at 4 substeps where a pixel's Y
// exceeds 0.02, 1.2% at worst on the darkest); a missed ray contributes 0.
void integratePixelAreas(const Setup& s, Image& image, const CentreRender& coarse)
{
  const View& view = s.ViewSettings;
  const AreaSetup a{ s, coarse.Picture.ViewSubsteps, darkFloor(image), Camera(view) };
  const auto width = static_cast<std::size_t>(view.Width), height = static_cast<std::size_t>(view.Height);
  std::vector<RaySample> corners((width + 1) * (height + 1));
  forEachPixel(corners.size(), [&](std::size_t i) {
    corners[i] = traceRay(s, a.Eye, static_cast<double>(i % (width + 1)), static_cast<double>(i / (width + 1)), a.Substeps, true);
  });
  forEachPixel(width * height, [&](std::size_t pixel) {
    const std::size_t x = pixel % width, y = pixel / width, c0 = y * (width + 1) + x;
    SquareRays q{ { corners[c0], corners[c0 + 1], corners[c0 + width + 1], corners[c0 + width + 2] }, {} };
    q.Centre.Hit = coarse.Picture.Hit[pixel] != 0;
    q.Centre.FirstDomain = coarse.FirstDomain[pixel];
    const std::array<double, 3> shine = highlightXYZ(s, image.Highlight[pixel]);
    for (std::size_t c = 0; c < 3; ++c)
      q.Centre.Body.XYZ[c] = coarse.Picture.XYZ[3 * pixel + c] - shine[c];
    const double scale = std::max(q.Centre.Body.XYZ[1], a.Floor);
    std::array<double, 3> mean = fivePointMean(q);
    if (!smoothSquare(q, mean, 1.0, scale, view.ConvergenceTolerance))
    {
      mean = squareMean(a, static_cast<double>(x), static_cast<double>(y), 1.0, q, view.AreaDepth, scale);
      image.Refined[pixel] = 1;
    }
    for (std::size_t c = 0; c < 3; ++c)
      image.XYZ[3 * pixel + c] += mean[c] - q.Centre.Body.XYZ[c];
  });
}
} // namespace

Image render(const Scene& scene, const View& view, const std::string& cieDirectory)
{
  const Volume volume(scene);
  const std::vector<Band> bands = wavelengthBands(view, cieDirectory);
  const dvec3 light(view.Light[0], view.Light[1], view.Light[2]);
  Setup setup{ volume, view, bands, light, apexDistanceSquared(volume, light), 1 };
  const std::vector<double> highlight = highlights(volume, view);
  // The renders so far, the latest last; the area pass takes the first's
  // centre rays (one body sample per voxel segment).
  std::vector<CentreRender> renders;
  renders.push_back(renderOnce(setup, highlight));
  if (!view.Converged)
    return std::move(renders.back().Picture);
  // The body's samples doubled until no pixel changes.
  for (setup.Substeps = 2;; setup.Substeps *= 2)
  {
    if (setup.Substeps > view.MaxViewSubsteps)
      throw std::runtime_error("the reference did not converge within " + std::to_string(view.MaxViewSubsteps) + " view sub-steps");
    renders.push_back(renderOnce(setup, highlight));
    const std::size_t last = renders.size() - 1;
    if (largestChange(renders[last - 1].Picture, renders[last].Picture) < view.ConvergenceTolerance)
    {
      integratePixelAreas(setup, renders[last].Picture, renders.front());
      return std::move(renders[last].Picture);
    }
  }
}

} // namespace opalreference
