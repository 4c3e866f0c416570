#include "OpalDomainLayout.h"

#include "OpalHalfEllipsoid.h"
#include "OpalLatticePlanes.h"
#include "OpalOptics.h"
#include "OpalRandom.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace opal
{

namespace
{

constexpr double DegToRad = Pi / 180.0;

// Step 1-2 of paper §3.2: a regular N-gon of circumradius R in the local xz
// plane, each vertex pulled towards the centre to a random point on its spoke;
// redrawn until every interior angle lies in the allowed range. Vertices are
// counter-clockwise as (x, z). Empty if no acceptable shape was found.
std::vector<glm::dvec2> drawPolygon(const ModelParameters& p, RandomSequence& random)
{
  const double minAngle = p.DomainAngleRange[0] * DegToRad;
  const double maxAngle = p.DomainAngleRange[1] * DegToRad;
  std::vector<glm::dvec2> polygon;
  for (int attempt = 0; attempt < p.MaxPlacementAttempts; ++attempt)
  {
    const int n = random.uniformInt(p.DomainVertexRange[0], p.DomainVertexRange[1]);
    const double radius = random.uniform(p.DomainRadiusRange[0], p.DomainRadiusRange[1]);
    polygon.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      const double spoke = radius * random.uniform(p.DomainVertexJitter[0], p.DomainVertexJitter[1]);
      const double angle = 2.0 * Pi * i / n;
      polygon[static_cast<std::size_t>(i)] = { spoke * std::cos(angle), spoke * std::sin(angle) };
    }
    bool acceptable = true;
    for (int i = 0; i < n && acceptable; ++i)
    {
      const glm::dvec2 previous = polygon[static_cast<std::size_t>((i + n - 1) % n)];
      const glm::dvec2 vertex = polygon[static_cast<std::size_t>(i)];
      const glm::dvec2 next = polygon[static_cast<std::size_t>((i + 1) % n)];
      const glm::dvec2 in = vertex - previous;
      const glm::dvec2 out = next - vertex;
      // The interior angle is pi minus the turn; a reflex vertex turns negatively.
      const double turn = std::atan2(in.x * out.y - in.y * out.x, glm::dot(in, out));
      const double interior = Pi - turn;
      acceptable = interior >= minAngle && interior <= maxAngle;
    }
    if (acceptable)
    {
      return polygon;
    }
  }
  return {};
}

// Step 3: tilt the normal from +y by `tilt`, spin about y by `spin`.
glm::dmat3 domainRotation(double tilt, double spin)
{
  const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), spin, glm::dvec3(0, 1, 0)) *
    glm::rotate(glm::dmat4(1.0), tilt, glm::dvec3(1, 0, 0));
  return glm::dmat3(rotation);
}

} // namespace

std::array<double, 3> tiltedNormal(double tilt, double spin)
{
  glm::dvec3 normal = domainRotation(tilt, spin) * glm::dvec3(0, 1, 0);
  if (normal.y < 0)
  {
    normal = -normal;
  }
  return { normal.x, normal.y, normal.z };
}

bool rasterisePolygon(const Grid& grid, const std::vector<std::array<double, 3>>& vertices,
  const std::array<double, 3>& normal, std::vector<std::array<int, 3>>& voxels)
{
  voxels.clear();
  // w: the grid axis closest to the normal; (u, v) span the columns.
  int w = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (std::fabs(normal[a]) > std::fabs(normal[w]))
    {
      w = a;
    }
  }
  const int u = (w + 1) % 3;
  const int v = (w + 2) % 3;
  double uMin = 1e300, uMax = -1e300, vMin = 1e300, vMax = -1e300;
  for (const auto& vertex : vertices)
  {
    uMin = std::min(uMin, vertex[u]);
    uMax = std::max(uMax, vertex[u]);
    vMin = std::min(vMin, vertex[v]);
    vMax = std::max(vMax, vertex[v]);
  }
  // Orientation of the projected polygon, so the inside test works either way round.
  const std::size_t n = vertices.size();
  double area = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& a = vertices[i];
    const auto& b = vertices[(i + 1) % n];
    area += a[u] * b[v] - b[u] * a[v];
  }
  const double orientation = area >= 0 ? 1.0 : -1.0;
  const auto& anchor = vertices[0];
  const int iuBegin = static_cast<int>(std::ceil((uMin - grid.Origin[u]) / grid.Spacing[u]));
  const int iuEnd = static_cast<int>(std::floor((uMax - grid.Origin[u]) / grid.Spacing[u]));
  const int ivBegin = static_cast<int>(std::ceil((vMin - grid.Origin[v]) / grid.Spacing[v]));
  const int ivEnd = static_cast<int>(std::floor((vMax - grid.Origin[v]) / grid.Spacing[v]));
  for (int iu = iuBegin; iu <= iuEnd; ++iu)
  {
    const double cu = grid.coordinate(u, iu);
    for (int iv = ivBegin; iv <= ivEnd; ++iv)
    {
      const double cv = grid.coordinate(v, iv);
      bool inside = true;
      for (std::size_t i = 0; i < n && inside; ++i)
      {
        const auto& a = vertices[i];
        const auto& b = vertices[(i + 1) % n];
        const double cross = (b[u] - a[u]) * (cv - a[v]) - (b[v] - a[v]) * (cu - a[u]);
        inside = orientation * cross >= 0;
      }
      if (!inside)
      {
        continue;
      }
      // The column's axis meets the plane n . (p - anchor) = 0 here.
      const double cw = anchor[w] -
        (normal[u] * (cu - anchor[u]) + normal[v] * (cv - anchor[v])) / normal[w];
      std::array<int, 3> voxel;
      voxel[u] = iu;
      voxel[v] = iv;
      voxel[w] = grid.voxelIndex(w, cw);
      if (!grid.contains(voxel[0], voxel[1], voxel[2]))
      {
        return false;
      }
      voxels.push_back(voxel);
    }
  }
  return true;
}

DomainLayout DomainLayout::build(
  const ModelParameters& p, const std::function<bool(double)>& progress, const CellAssignment& assignment)
{
  DomainLayout layout =
    p.DomainLayout == DomainLayoutKind::Voronoi ? buildVoronoi(p, progress, assignment) : buildPolygons(p, progress);
  // Step 6 (docs/design.md §2.4): the spin from a stream of its own, counter =
  // the domain's id, so the layout's own draws (and today's volumes) stay as they were.
  for (Domain& domain : layout.Domains)
  {
    domain.LatticeSpin =
      2.0 * Pi * unitFromHash(hashCounter(p.Seed, RandomStream::LatticeSpin, static_cast<std::uint64_t>(domain.Id)));
  }
  return layout;
}

std::array<double, 4> latticeQuaternion(const Domain& domain)
{
  const glm::dquat q =
    latticeOrientation(glm::dvec3(domain.Normal[0], domain.Normal[1], domain.Normal[2]), domain.LatticeSpin);
  return { q.w, q.x, q.y, q.z };
}

DomainLayout DomainLayout::buildPolygons(const ModelParameters& p, const std::function<bool(double)>& progress)
{
  DomainLayout layout;
  layout.Requested = p.DomainCount;
  const Grid grid = Grid::fromParameters(p);
  const HalfEllipsoid shape(p.SemiAxes);
  RandomSequence random(p.Seed, RandomStream::DomainLayout);
  std::unordered_set<std::int64_t> occupied;
  std::vector<std::array<int, 3>> voxels;
  std::vector<std::array<double, 3>> vertices;

  for (int d = 0; d < p.DomainCount; ++d)
  {
    if (progress && !progress(static_cast<double>(d) / p.DomainCount))
    {
      layout.Aborted = true;
      break;
    }
    const std::vector<glm::dvec2> polygon = drawPolygon(p, random);
    if (polygon.empty())
    {
      continue;
    }
    const double diameter = random.uniform(p.DomainDiameterRange[0], p.DomainDiameterRange[1]);
    for (int attempt = 0; attempt < p.MaxPlacementAttempts; ++attempt)
    {
      const double tilt = random.uniform(p.DomainRotationRange[0], p.DomainRotationRange[1]) * DegToRad;
      const double spin = random.uniform(0.0, 360.0) * DegToRad;
      // A random position inside the opal: uniform in its bounding box.
      const std::array<double, 3> centre{ random.uniform(-p.SemiAxes[0], p.SemiAxes[0]),
        random.uniform(0.0, p.SemiAxes[1]), random.uniform(-p.SemiAxes[2], p.SemiAxes[2]) };
      if (!shape.contains(centre))
      {
        continue;
      }
      const glm::dmat3 rotation = domainRotation(tilt, spin);
      const std::array<double, 3> n = tiltedNormal(tilt, spin);
      vertices.clear();
      for (const glm::dvec2& local : polygon)
      {
        const glm::dvec3 world = rotation * glm::dvec3(local.x, 0, local.y);
        vertices.push_back({ world.x + centre[0], world.y + centre[1], world.z + centre[2] });
      }
      if (!rasterisePolygon(grid, vertices, n, voxels) || voxels.empty())
      {
        continue;
      }
      // Step 5: every voxel must be a free voxel of the opal, else redraw.
      const bool free = std::all_of(voxels.begin(), voxels.end(), [&](const std::array<int, 3>& v) {
        return shape.contains(grid.position(v[0], v[1], v[2])) &&
          occupied.count(grid.linearIndex(v[0], v[1], v[2])) == 0;
      });
      if (!free)
      {
        continue;
      }
      Domain domain;
      domain.Id = static_cast<int>(layout.Domains.size());
      domain.Vertices = vertices;
      domain.Normal = n;
      domain.ParticleDiameter = diameter;
      for (const auto& v : voxels)
      {
        const std::int64_t index = grid.linearIndex(v[0], v[1], v[2]);
        occupied.insert(index);
        layout.Voxels.push_back({ index, domain.Id });
      }
      layout.Domains.push_back(std::move(domain));
      break;
    }
  }
  std::sort(layout.Voxels.begin(), layout.Voxels.end());
  return layout;
}

std::vector<DomainVoxel>::const_iterator DomainLayout::lowerBound(std::int64_t index) const
{
  return std::lower_bound(this->Voxels.begin(), this->Voxels.end(), DomainVoxel{ index, -1 });
}

} // namespace opal
