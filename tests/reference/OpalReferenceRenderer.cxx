#include "OpalReferenceRenderer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
  {
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
    return this->voxel(p, c) ? this->S.Scattering[this->index(c[0], c[1], c[2])] : 0.0;
  }

  // Trilinear SurfaceDistance between voxel centres, continued linearly beyond them.
  double distance(const dvec3& p) const
  {
    double g[3];
    int c0[3], c1[3];
    dvec3 nearest(0.0);
    for (int a = 0; a < 3; ++a)
    {
      const double lo = this->S.Origin[a];
      const double hi = lo + (this->S.Dimensions[a] - 1) * this->S.Spacing[a];
      nearest[a] = std::min(std::max(p[a], lo), hi);
      g[a] = (nearest[a] - lo) / this->S.Spacing[a];
      c0[a] = std::min(static_cast<int>(std::floor(g[a])), std::max(this->S.Dimensions[a] - 2, 0));
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
  double entry(const dvec3& o, const dvec3& d) const
  {
    const auto [t0, t1] = this->box(o, d);
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
};

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

// Light reaching p (eq. 6, 7 with docs/design.md §4.1's 1/r^2 to the sample), at 550 nm
// optical depth tau and geometric factor g: march towards the light one voxel
// length at a time, nearest-voxel coefficients at each step's midpoint, until
// the path leaves the opal at L_in, where the Fresnel transmission applies.
void lightAt(const Volume& v, const dvec3& p, const dvec3& light, double apexDistance2, double mu, double& tau, double& g)
{
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
      tau += v.scattering(p + 0.5 * (t + exit) * d) * (exit - t);
      break;
    }
    tau += v.scattering(p + (t + 0.5 * step) * d) * step;
    t += step;
  }
  const dvec3 entry = p + exit * d;
  const double r2 = glm::dot(light - p, light - p);
  g = (1 - fresnel(glm::dot(v.normal(entry), d), mu)) * apexDistance2 / r2;
}
} // namespace

Image render(const Scene& scene, const View& view, const std::string& cieDirectory)
{
  const Volume volume(scene);
  const std::vector<Band> bands = wavelengthBands(view, cieDirectory);
  const dvec3 eye(view.Eye[0], view.Eye[1], view.Eye[2]);
  const dvec3 light(view.Light[0], view.Light[1], view.Light[2]);
  const dvec3 forward = glm::normalize(dvec3(view.FocalPoint[0], view.FocalPoint[1], view.FocalPoint[2]) - eye);
  const dvec3 right = glm::normalize(glm::cross(forward, dvec3(view.ViewUp[0], view.ViewUp[1], view.ViewUp[2])));
  const dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(view.ViewAngle * Pi / 360.0);
  const double aspect = static_cast<double>(view.Width) / view.Height;
  const double mu = view.RefractiveIndex;
  const double h = volume.minSpacing();

  // Irradiance 1 at the apex: the top of the surface over the grid's centre column.
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
  const double apexDistance2 = glm::dot(light - apex, light - apex);
  const double lightRadiance = apexDistance2 / (Pi * view.LightRadius * view.LightRadius);

  auto direction = [&](double x, double y) {
    const double nx = 2 * x / view.Width - 1, ny = 1 - 2 * y / view.Height;
    return glm::normalize(forward + nx * tanHalf * aspect * right + ny * tanHalf * up);
  };

  Image image;
  const std::size_t pixels = static_cast<std::size_t>(view.Width) * view.Height;
  image.XYZ.assign(3 * pixels, 0.0);
  image.Dominant.assign(pixels, 0.0);
  image.Hit.assign(pixels, 0);
  image.CosIncidence.assign(pixels, 0.0);
  image.Highlight.assign(pixels, 0.0);
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const std::size_t pixel = static_cast<std::size_t>(py) * view.Width + px;
      const dvec3 d = direction(px + 0.5, py + 0.5);
      const double tHit = volume.entry(eye, d);
      if (tHit < 0)
        continue;
      image.Hit[pixel] = 1;
      const dvec3 hit = eye + tHit * d;
      const dvec3 n = volume.normal(hit);
      const double transmitted = 1 - fresnel(-glm::dot(d, n), mu);
      image.CosIncidence[pixel] = -glm::dot(d, n);

      // The highlight: the light's mirror image, over n x n sub-rays of the pixel.
      double highlight = 0;
      const int s = view.SpecularSamples;
      for (int sy = 0; sy < s; ++sy)
        for (int sx = 0; sx < s; ++sx)
        {
          const dvec3 sd = direction(px + (sx + 0.5) / s, py + (sy + 0.5) / s);
          const double st = volume.entry(eye, sd);
          if (st < 0)
            continue;
          const dvec3 sp = eye + st * sd;
          const dvec3 sn = volume.normal(sp);
          const dvec3 mirrored = glm::reflect(sd, sn);
          const double along = glm::dot(light - sp, mirrored);
          if (-glm::dot(sd, sn) > 0 && along > 0 && glm::length(sp + along * mirrored - light) <= view.LightRadius)
            highlight += fresnel(-glm::dot(sd, sn), mu) / (s * s);
        }

      image.Highlight[pixel] = highlight;

      // The refracted ray and where it leaves the opal.
      const dvec3 inward = glm::refract(d, n, 1.0 / mu);
      const dvec3 origin = hit - 1e-4 * h * n;
      double tExit = volume.box(origin, inward)[1];
      for (double t = 0; t < tExit; t += 0.02 * h)
      {
        if (volume.distance(origin + t * inward) > 0)
        {
          tExit = volume.bisect(origin, inward, std::max(0.0, t - 0.02 * h), t, false);
          break;
        }
      }

      // Voxel-by-voxel segments of the refracted ray (the same for every wavelength).
      struct Segment
      {
        double T0, T1;
        int Voxel;
      };
      std::vector<Segment> segments;
      {
        int c[3];
        volume.voxel(origin, c);
        double t = 0;
        while (t < tExit)
        {
          double next = tExit;
          for (int a = 0; a < 3; ++a)
          {
            if (inward[a] == 0)
              continue;
            const double boundary = scene.Origin[a] + (c[a] + (inward[a] > 0 ? 0.5 : -0.5)) * scene.Spacing[a];
            next = std::min(next, (boundary - origin[a]) / inward[a]);
          }
          next = std::max(next, t);
          const bool inside = c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < scene.Dimensions[0] &&
            c[1] < scene.Dimensions[1] && c[2] < scene.Dimensions[2];
          if (next > t && inside)
            segments.push_back({ t, next, static_cast<int>(volume.index(c[0], c[1], c[2])) });
          if (next >= tExit)
            break;
          // Step into the neighbour across the nearest boundary.
          int axis = 0;
          double best = 1e300;
          for (int a = 0; a < 3; ++a)
          {
            if (inward[a] == 0)
              continue;
            const double boundary = scene.Origin[a] + (c[a] + (inward[a] > 0 ? 0.5 : -0.5)) * scene.Spacing[a];
            const double tb = (boundary - origin[a]) / inward[a];
            if (tb < best)
            {
              best = tb;
              axis = a;
            }
          }
          c[axis] += inward[axis] > 0 ? 1 : -1;
          t = next;
        }
      }

      // Every wavelength separately (the paper's cost).
      std::vector<double> crossingY, crossingLambda;
      for (const Band& band : bands)
      {
        const double rayleigh = std::pow(550.0 / band.Lambda, 4.0);
        double radiance = 0, tauView = 0;
        int lastDomain = -1, crossing = 0;
        for (const Segment& segment : segments)
        {
          const double length = segment.T1 - segment.T0;
          const dvec3 middle = origin + 0.5 * (segment.T0 + segment.T1) * inward;
          const int domain = scene.DomainId[static_cast<std::size_t>(segment.Voxel)];
          if (domain >= 0)
          {
            if (domain != lastDomain)
            {
              // Bragg-Snell (eq. 4, 9): the box band averaged over this bin.
              const auto& lattice = scene.Domains[static_cast<std::size_t>(domain)];
              const dvec3 normal(lattice[0], lattice[1], lattice[2]);
              const double sinGlancing = std::fabs(glm::dot(glm::normalize(light - middle), normal));
              const double lambdaB = 2 * lattice[3] * std::sqrt(std::max(mu * mu - (1 - sinGlancing * sinGlancing), 0.0));
              const double lo = std::max(band.Lambda - 0.5 * band.Width, lambdaB * (1 - 0.5 * view.BraggBandwidth));
              const double hi = std::min(band.Lambda + 0.5 * band.Width, lambdaB * (1 + 0.5 * view.BraggBandwidth));
              const double b = std::max(hi - lo, 0.0) / band.Width;
              double tau, g;
              lightAt(volume, middle, light, apexDistance2, mu, tau, g);
              const double value = view.DiffractionGain * b * g * std::exp(-(tau * rayleigh + tauView)) / Pi;
              radiance += value;
              if (crossingY.size() <= static_cast<std::size_t>(crossing))
              {
                crossingY.push_back(0);
                crossingLambda.push_back(lambdaB);
              }
              crossingY[static_cast<std::size_t>(crossing)] += value * band.D65 * band.Y * band.Width;
              ++crossing;
              lastDomain = domain;
            }
            continue;
          }
          lastDomain = -1;
          const double mus = scene.Scattering[static_cast<std::size_t>(segment.Voxel)] * rayleigh;
          if (mus <= 0)
            continue;
          // Rayleigh single scattering (eq. 8), phase 1/(4 pi), T_V at the midpoint.
          double tau, g;
          lightAt(volume, middle, light, apexDistance2, mu, tau, g);
          radiance += g * std::exp(-tau * rayleigh) * mus / (4 * Pi) * length * std::exp(-(tauView + 0.5 * mus * length));
          tauView += mus * length;
        }
        const double total = (transmitted * radiance + highlight * lightRadiance) * band.D65;
        image.XYZ[3 * pixel] += total * band.X * band.Width;
        image.XYZ[3 * pixel + 1] += total * band.Y * band.Width;
        image.XYZ[3 * pixel + 2] += total * band.Z * band.Width;
      }
      // The dominant Bragg wavelength: the crossing whose light has the most luminance.
      const auto brightest = std::max_element(crossingY.begin(), crossingY.end());
      if (brightest != crossingY.end() && *brightest > 0)
      {
        image.Dominant[pixel] = crossingLambda[static_cast<std::size_t>(brightest - crossingY.begin())];
      }
    }
  }
  return image;
}

} // namespace opalreference
