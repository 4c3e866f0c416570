#include "OpalScatteredLight.h"

#include "OpalOptics.h"
#include "OpalParallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace opal
{

namespace
{
// Flights and reflections one photon may make per collision of its budget
// (virtual collisions included).
constexpr int EventsPerCollision = 100;
// Rounds of the solve: progress and cancellation are checked between them.
constexpr int Rounds = 8;
// Photons of a round's node run in this many tasks, interleaved over nodes so
// that every thread gets every node's share (the blue nodes cost the most).
constexpr int TasksPerNode = 4;
// A share of the entered power given up above this is reported.
constexpr double ReportedShortfall = 1e-3;

// splitmix64: a photon's random numbers derive from its global index alone.
struct PhotonRandom
{
  std::uint64_t State;

  double uniform()
  {
    std::uint64_t z = (this->State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
  }
};

glm::dvec3 isotropicDirection(PhotonRandom& random)
{
  const double cosTheta = 2.0 * random.uniform() - 1.0;
  const double phi = 2.0 * Pi * random.uniform();
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return { sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta };
}

} // namespace

ScatteredLightGrid scatteredLightGrid(const VolumeGeometry& geometry)
{
  return scatteredLightGrid(geometry.dimensions());
}

ScatteredLightGrid scatteredLightGrid(const glm::ivec3& dims)
{
  const int longest = std::max({ dims.x, dims.y, dims.z });
  ScatteredLightGrid grid;
  grid.Stride = std::max(1, (longest + ScatteredLightCellsAlongLongestSide - 1) / ScatteredLightCellsAlongLongestSide);
  grid.Nodes = (dims - 1 + grid.Stride - 1) / grid.Stride + 1;
  return grid;
}

namespace
{
// The coarse grid the flights score on: node n sits on voxel centre n * Stride.
struct TallyGrid
{
  glm::ivec3 Nodes{ 1 };
  int Stride = 1;
  glm::dvec3 Origin{ 0.0 }, Spacing{ 1.0 }; // of the voxel grid

  explicit TallyGrid(const VolumeGeometry& geometry)
    : Nodes(scatteredLightGrid(geometry).Nodes)
    , Stride(scatteredLightGrid(geometry).Stride)
    , Origin(geometry.origin())
    , Spacing(geometry.spacing())
  {
  }

  std::size_t size() const { return static_cast<std::size_t>(this->Nodes.x) * this->Nodes.y * this->Nodes.z; }

  // Calls visit(node index, trilinear weight) for the eight nodes around p.
  template <typename Visit>
  void forEachNode(const glm::dvec3& p, Visit&& visit) const
  {
    const glm::dvec3 g = glm::clamp((p - this->Origin) / (this->Spacing * double(this->Stride)), glm::dvec3(0.0),
      glm::dvec3(this->Nodes - 1));
    const glm::ivec3 c0 = glm::min(glm::ivec3(glm::floor(g)), glm::max(this->Nodes - 2, glm::ivec3(0)));
    this->visitCorners(c0, glm::clamp(g - glm::dvec3(c0), 0.0, 1.0), visit);
  }

  // The same for the centre of voxel `voxel`, its weights from the index
  // alone: exactly 0 for a node whose cells do not reach the voxel. Weights
  // from the position carried rounding (1e-16 where 0 was meant), which gave
  // nodes far outside the stone inside volumes of 1e-33 mm^3 beside real
  // tallies, and voxels next to them values 10^14 times their neighbours'.
  template <typename Visit>
  void forEachNodeOfVoxel(const glm::ivec3& voxel, Visit&& visit) const
  {
    const glm::ivec3 c0 = glm::min(voxel / this->Stride, glm::max(this->Nodes - 2, glm::ivec3(0)));
    this->visitCorners(c0, glm::min(glm::dvec3(voxel - c0 * this->Stride) / double(this->Stride), 1.0), visit);
  }

  template <typename Visit>
  void visitCorners(const glm::ivec3& c0, const glm::dvec3& f, Visit& visit) const
  {
    for (int corner = 0; corner < 8; ++corner)
    {
      const glm::ivec3 o((corner & 1), (corner >> 1) & 1, (corner >> 2) & 1);
      const glm::ivec3 n = glm::min(c0 + o, this->Nodes - 1);
      visit(static_cast<std::size_t>(n.x + this->Nodes.x * (n.y + this->Nodes.y * n.z)),
        (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z));
    }
  }

  // Adds `value` to the eight nodes around p with trilinear (cloud-in-cell) weights.
  void deposit(std::vector<double>& tally, const glm::dvec3& p, double value) const
  {
    this->forEachNode(p, [&](std::size_t n, double w) { tally[n] += w * value; });
  }

  // Adds a flight's track, `weight` times its length, spread along it at
  // points at most half a cell apart (a randomly shifted midpoint rule:
  // unbiased, and smooth however thin the medium).
  void depositTrack(std::vector<double>& tally, const glm::dvec3& from, const glm::dvec3& to, double weight,
    double shift) const
  {
    const double length = glm::length(to - from);
    const double cell = std::min({ this->Spacing.x, this->Spacing.y, this->Spacing.z }) * this->Stride;
    const int points = std::max(1, static_cast<int>(std::ceil(2.0 * length / cell)));
    for (int k = 0; k < points; ++k)
    {
      this->deposit(tally, glm::mix(from, to, (k + shift) / points), weight * length / points);
    }
  }
};

// A ball about a point inside the medium that the surface does not enter
// (0.9 of SurfaceDistance there, as the march's sphere tracing takes it): a
// flight that ends inside it needs no look at the surface. Most flights
// are short against the stone, so most skip the field's reads.
struct SafeBall
{
  glm::dvec3 Centre{ 0.0 };
  double Radius = 0;

  bool contains(const glm::dvec3& q) const
  {
    const glm::dvec3 d = q - this->Centre;
    return glm::dot(d, d) < this->Radius * this->Radius;
  }
};

// What one task's photons scored and where their power went.
struct TaskScore
{
  std::vector<double> Tally;
  double Entered = 0, Escaped = 0, Absorbed = 0, GivenUp = 0;
};

// The photons of one spectral node: the medium's extinction at its s.
class NodeTransport
{
public:
  NodeTransport(const ScatteringMedium& medium, const ScatteredLightRequest& request, const TallyGrid& tally,
    double scale)
    : Medium(medium), Request(request), Tally(tally), Scale(scale)
    , ColouredScale(std::pow(scale, 0.25 * medium.AbsorptionExponent))
    , Step(0.25 * medium.Geometry.smallestSpacing())
  {
    for (std::size_t i = 0; i < medium.Scattering.size(); ++i)
    {
      this->Majorant = std::max(this->Majorant, this->extinction(i).first);
    }
  }

  void trace(std::int64_t photon, std::int64_t photons, TaskScore& score) const;

private:
  // (mu_t, mu_s) of voxel i at this node's wavelength.
  std::pair<double, double> extinction(std::size_t i) const
  {
    const double scattering = this->Scale * this->Medium.Scattering[i];
    if (this->Medium.Absorption.empty())
    {
      return { scattering, scattering };
    }
    const glm::vec2& a = this->Medium.Absorption[i];
    return { scattering + this->ColouredScale * a[0] + a[1], scattering };
  }

  std::size_t voxelOf(const glm::dvec3& p) const
  {
    const VolumeGeometry& g = this->Medium.Geometry;
    const glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor((p - g.origin()) / g.spacing() + 0.5)), glm::ivec3(0),
      g.dimensions() - 1);
    return static_cast<std::size_t>(c.x) + static_cast<std::size_t>(g.dimensions().x) *
      (static_cast<std::size_t>(c.y) + static_cast<std::size_t>(g.dimensions().y) * static_cast<std::size_t>(c.z));
  }

  // How far p lies inside the medium: inside the smooth surface and the grid's
  // box, where the render's medium ends too; negative outside.
  double depth(const glm::dvec3& p) const
  {
    const VolumeGeometry& g = this->Medium.Geometry;
    const glm::dvec3 toBox = glm::min(p - g.boxLow(), g.boxHigh() - p);
    return std::min({ -g.surfaceDistance(p), toBox.x, toBox.y, toBox.z });
  }

  // The outward normal at a surface point: a face's where the box is nearer than the surface.
  glm::dvec3 normalAt(const glm::dvec3& p) const;

  bool enter(PhotonRandom& random, glm::dvec3& p, glm::dvec3& direction, double& weight) const;
  template <typename Visit>
  void walkChord(const glm::dvec3& p, const glm::dvec3& direction, Visit&& visit) const;
  void scatterFirst(PhotonRandom& random, glm::dvec3& p, const glm::dvec3& direction, double& weight,
    TaskScore& score) const;
  bool flyTo(glm::dvec3& p, const glm::dvec3& direction, double distance, SafeBall& ball) const;
  bool staysInside(PhotonRandom& random, glm::dvec3& p, glm::dvec3& direction) const;
  glm::dvec3 surfaceBetween(glm::dvec3 inside, glm::dvec3 outside) const;

  const ScatteringMedium& Medium;
  const ScatteredLightRequest& Request;
  const TallyGrid& Tally;
  double Scale, ColouredScale, Step;
  double Majorant = 0;
};

glm::dvec3 NodeTransport::normalAt(const glm::dvec3& p) const
{
  const VolumeGeometry& g = this->Medium.Geometry;
  const glm::dvec3 below = p - g.boxLow(), above = g.boxHigh() - p;
  double nearest = -g.surfaceDistance(p);
  glm::dvec3 normal = g.surfaceNormal(p);
  for (int a = 0; a < 3; ++a)
  {
    glm::dvec3 face(0.0);
    if (below[a] < nearest)
    {
      nearest = below[a];
      face[a] = -1.0;
      normal = face;
    }
    if (above[a] < nearest)
    {
      nearest = above[a];
      face[a] = 1.0;
      normal = face;
    }
  }
  return normal;
}

// The crossing of the surface between an inside and an outside point (bisection).
glm::dvec3 NodeTransport::surfaceBetween(glm::dvec3 inside, glm::dvec3 outside) const
{
  for (int i = 0; i < 24; ++i)
  {
    const glm::dvec3 middle = 0.5 * (inside + outside);
    (this->depth(middle) < 0 ? outside : inside) = middle;
  }
  return inside;
}

// Moves p by `distance` along the direction unless the surface comes first:
// then p stops just inside it and the result is false. Within `ball` at
// once; else in steps as far as SurfaceDistance guarantees to stay inside
// (sphere tracing), at least a quarter voxel, and the ball moves to the end.
bool NodeTransport::flyTo(glm::dvec3& p, const glm::dvec3& direction, double distance, SafeBall& ball) const
{
  const glm::dvec3 end = p + distance * direction;
  if (ball.contains(p) && ball.contains(end)) // the ball is convex: the whole flight lies in it
  {
    p = end;
    return true;
  }
  while (distance > 0)
  {
    const double step = std::min(distance, std::max(0.9 * this->depth(p), this->Step));
    const glm::dvec3 q = p + step * direction;
    if (this->depth(q) < 0)
    {
      p = this->surfaceBetween(p, q);
      return false;
    }
    p = q;
    distance -= step;
  }
  ball = SafeBall{ p, 0.9 * this->depth(p) };
  return true;
}

// A photon from the light towards the grid's bounding sphere (uniform in
// that cone), carried straight to where it meets the surface and through it
// with 1 - F (the direct light field's entry, docs/design.md §3.3). False if
// it misses the stone. `weight` arrives as the photon's share of the cone.
bool NodeTransport::enter(PhotonRandom& random, glm::dvec3& p, glm::dvec3& direction, double& weight) const
{
  const VolumeGeometry& g = this->Medium.Geometry;
  const glm::dvec3 low = g.boxLow(), high = g.boxHigh();
  const glm::dvec3 centre = 0.5 * (low + high);
  const glm::dvec3 axis = glm::normalize(centre - this->Request.Light);
  const double radius = 0.5 * glm::length(high - low), distance = glm::length(centre - this->Request.Light);
  const double cosCone = distance > radius ? std::sqrt(1.0 - radius * radius / (distance * distance)) : -1.0;
  const double cosTheta = 1.0 - random.uniform() * (1.0 - cosCone), phi = 2.0 * Pi * random.uniform();
  const glm::dvec3 side = glm::normalize(glm::cross(axis, std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(axis, side);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  direction = cosTheta * axis + sinTheta * (std::cos(phi) * side + std::sin(phi) * up);
  weight *= 2.0 * Pi * (1.0 - cosCone);
  // The ray's stretch inside the box (slabs), then the first zero of SurfaceDistance on it.
  double t0 = 0, t1 = 1e30;
  for (int a = 0; a < 3; ++a)
  {
    const double inverse = 1.0 / direction[a];
    const double near = (low[a] - this->Request.Light[a]) * inverse, far = (high[a] - this->Request.Light[a]) * inverse;
    t0 = std::max(t0, std::min(near, far));
    t1 = std::min(t1, std::max(near, far));
  }
  for (double t = t0; t < t1;)
  {
    const glm::dvec3 q = this->Request.Light + t * direction;
    const double d = g.surfaceDistance(q);
    if (d <= 0)
    {
      p = this->surfaceBetween(q, this->Request.Light + std::max(t0, t - 2 * this->Step) * direction);
      const double cosIncidence = -glm::dot(direction, this->normalAt(p));
      weight *= 1.0 - fresnelReflectance(cosIncidence, this->Request.RefractiveIndex);
      return true;
    }
    t += std::max(0.9 * d, this->Step);
  }
  return false;
}

// Visits the straight chord from p to where it leaves the medium in steps of
// half the smallest spacing, as visit(start, length, extinction) with each
// step's extinction at its midpoint's voxel, while visit returns true.
template <typename Visit>
void NodeTransport::walkChord(const glm::dvec3& p, const glm::dvec3& direction, Visit&& visit) const
{
  const double step = 2.0 * this->Step;
  SafeBall ball{ p, 0.9 * this->depth(p) };
  for (glm::dvec3 q = p;;)
  {
    glm::dvec3 next = q + step * direction;
    const bool leaves = !ball.contains(next) && (ball = SafeBall{ next, 0.9 * this->depth(next) }).Radius < 0;
    if (leaves)
    {
      next = this->surfaceBetween(q, next);
    }
    const double length = glm::length(next - q);
    if (!visit(q, length, this->extinction(this->voxelOf(0.5 * (q + next))).first) || leaves)
    {
      return;
    }
    q = next;
  }
}

// The entered photon's first collision, forced (every photon scatters, the
// share of it that would pass unscattered leaves): the point drawn from the
// truncated exponential of the optical depth along its straight chord. A
// thin stone's scattered light so comes from every photon, not the few that
// scatter by chance.
void NodeTransport::scatterFirst(
  PhotonRandom& random, glm::dvec3& p, const glm::dvec3& direction, double& weight, TaskScore& score) const
{
  double chordDepth = 0;
  this->walkChord(p, direction, [&](const glm::dvec3&, double length, double mu) {
    chordDepth += mu * length;
    return true;
  });
  const double collides = -std::expm1(-chordDepth);
  score.Escaped += weight * (1.0 - collides);
  weight *= collides;
  const double target = -std::log1p(-random.uniform() * collides);
  double reached = 0;
  this->walkChord(p, direction, [&](const glm::dvec3& start, double length, double mu) {
    if (mu * length < target - reached || mu <= 0)
    {
      reached += mu * length;
      p = start + length * direction;
      return true;
    }
    p = start + (target - reached) / mu * direction;
    return false;
  });
  const auto [extinction, scattering] = this->extinction(this->voxelOf(p));
  const double kept = extinction > 0 ? scattering / extinction : 0.0;
  score.Absorbed += weight * (1.0 - kept);
  weight *= kept;
}

// A photon at the surface from inside: reflected back in with Fresnel's
// probability (certainly beyond the critical angle), or it leaves (false).
bool NodeTransport::staysInside(PhotonRandom& random, glm::dvec3& p, glm::dvec3& direction) const
{
  const glm::dvec3 normal = this->normalAt(p);
  const double cosInside = glm::dot(direction, normal);
  if (cosInside <= 0)
  {
    // Leaving by the crossing but inward by the gradient (a grazing ray in a
    // corner of the sampled surface): stepped back inside, it flies on.
    p -= this->Step * normal;
    return true;
  }
  if (random.uniform() < internalFresnelReflectance(cosInside, this->Request.RefractiveIndex))
  {
    direction -= 2.0 * cosInside * normal;
    return true;
  }
  return false;
}

// Photon `photon` of `photons`: enters, flies (delta tracking against the
// majorant), scatters, is reflected inside or leaves; every flight after the
// first collision, to a real or virtual collision or the surface, scores its
// track length times its weight.
void NodeTransport::trace(std::int64_t photon, std::int64_t photons, TaskScore& score) const
{
  PhotonRandom random{ this->Request.Seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(photon) };
  glm::dvec3 p, direction;
  double weight = this->Request.LightStrength / static_cast<double>(photons);
  if (this->Majorant <= 0 || !this->enter(random, p, direction, weight))
  {
    return;
  }
  score.Entered += weight;
  this->scatterFirst(random, p, direction, weight, score);
  const double rouletteBelow = 0.01 * weight;
  direction = isotropicDirection(random);
  SafeBall ball{ p, 0.9 * this->depth(p) };
  for (int collisions = 1, events = 0; weight > 0; ++events)
  {
    if (collisions > this->Request.CollisionBudget || events > EventsPerCollision * this->Request.CollisionBudget)
    {
      score.GivenUp += weight;
      return;
    }
    const double flight = -std::log(1.0 - random.uniform()) / this->Majorant;
    const glm::dvec3 from = p;
    const bool collided = this->flyTo(p, direction, flight, ball);
    this->Tally.depositTrack(score.Tally, from, p, weight, random.uniform());
    if (!collided)
    {
      if (this->staysInside(random, p, direction))
      {
        continue;
      }
      score.Escaped += weight;
      return;
    }
    const auto [extinction, scattering] = this->extinction(this->voxelOf(p));
    if (random.uniform() * this->Majorant >= extinction)
    {
      continue; // a virtual collision
    }
    const double kept = scattering / extinction;
    score.Absorbed += weight * (1.0 - kept);
    weight *= kept;
    ++collisions;
    direction = isotropicDirection(random);
    // Russian roulette: a dim photon lives on doubled or ends (unbiased; the
    // absorbing media alone dim photons).
    if (weight < rouletteBelow && (weight *= 2.0, random.uniform() < 0.5))
    {
      return;
    }
  }
}

// The fluence per node: each node's tally over the inside volume that the
// same trilinear weights give it (a kernel estimate, unbiased at the surface
// where a node's cells lie partly outside). In VolumeBlocks z-slabs over the
// threads, each into its own sums, added in slab order: the sums never depend
// on the thread count (one thread over 2.56 G voxels would take seconds).
constexpr int VolumeBlocks = 64;

std::vector<double> insideVolumes(const VolumeGeometry& g, const TallyGrid& tally)
{
  const glm::ivec3 dims = g.dimensions();
  const double cell = g.spacing().x * g.spacing().y * g.spacing().z;
  const int blocks = std::min(VolumeBlocks, dims.z);
  std::vector<std::vector<double>> sums(static_cast<std::size_t>(blocks));
  parallelFor(0, blocks, [&](int begin, int end) {
    for (int b = begin; b < end; ++b)
    {
      std::vector<double>& volumes = sums[static_cast<std::size_t>(b)];
      volumes.assign(tally.size(), 0.0);
      for (int k = dims.z * b / blocks; k < dims.z * (b + 1) / blocks; ++k)
        for (int j = 0; j < dims.y; ++j)
          for (int i = 0; i < dims.x; ++i)
          {
            if (g.insideVoxel(i, j, k))
            {
              tally.forEachNodeOfVoxel({ i, j, k }, [&](std::size_t n, double w) { volumes[n] += w * cell; });
            }
          }
    }
  });
  std::vector<double> volumes(tally.size(), 0.0);
  for (const std::vector<double>& block : sums)
  {
    std::transform(block.begin(), block.end(), volumes.begin(), volumes.begin(), std::plus<>());
  }
  return volumes;
}

// The share that traces task t: tasks interleave the nodes (t % nodes), so
// dealing (t / nodes + t % nodes) % shares gives each share every node alike
// where it can (the blue nodes cost the most).
int taskShare(int task, int shares)
{
  return (task / ScatteredLightNodes + task % ScatteredLightNodes) % shares;
}

std::vector<int> tasksOfShare(int share, int shares)
{
  std::vector<int> tasks;
  for (int t = 0; t < ScatteredLightNodes * TasksPerNode; ++t)
  {
    if (taskShare(t, shares) == share)
    {
      tasks.push_back(t);
    }
  }
  return tasks;
}

// A task's score packed: its four powers, then its tally.
constexpr std::size_t PackedPowers = 4;

void packScore(const TaskScore& score, std::vector<double>& packed)
{
  packed.insert(packed.end(), { score.Entered, score.Escaped, score.Absorbed, score.GivenUp });
  packed.insert(packed.end(), score.Tally.begin(), score.Tally.end());
}

const double* unpackScore(const double* packed, std::size_t tallySize, TaskScore& score)
{
  score.Entered = packed[0];
  score.Escaped = packed[1];
  score.Absorbed = packed[2];
  score.GivenUp = packed[3];
  score.Tally.assign(packed + PackedPowers, packed + PackedPowers + tallySize);
  return packed + PackedPowers + tallySize;
}
} // namespace

std::vector<double> scatteredLightNodeVolumes(const VolumeGeometry& geometry)
{
  return insideVolumes(geometry, TallyGrid(geometry));
}

std::array<double, ScatteredLightNodes> scatteredLightScales(double shortestNm, double longestNm)
{
  // Evenly in sqrt(s) = (550/lambda)^2: log J/s is then interpolated within
  // 1.6% for power laws s^(+-0.5) and exactly for exp(-b s), against 10% for
  // the power laws with nodes evenly in s (docs/design.md §3.10).
  const double first = std::pow(ReferenceWavelengthNm / longestNm, 2.0);
  const double last = std::pow(ReferenceWavelengthNm / shortestNm, 2.0);
  std::array<double, ScatteredLightNodes> scales{};
  for (int m = 0; m < ScatteredLightNodes; ++m)
  {
    const double root = first + (last - first) * m / (ScatteredLightNodes - 1);
    scales[m] = root * root;
  }
  return scales;
}

std::optional<std::vector<double>> traceScatteredLightShare(const ScatteringMedium& medium,
  const ScatteredLightRequest& request, int share, int shares, const std::function<bool(double)>& keepGoing)
{
  if (shares < 1 || share < 0 || share >= shares)
  {
    throw std::invalid_argument("The scattered light's share " + std::to_string(share) + " of " +
      std::to_string(shares) + " does not exist.");
  }
  const TallyGrid tally(medium.Geometry);
  std::vector<NodeTransport> nodes;
  for (int m = 0; m < ScatteredLightNodes; ++m)
  {
    nodes.emplace_back(medium, request, tally, request.NodeScales[m]);
  }
  const std::vector<int> tasks = tasksOfShare(share, shares);
  std::vector<TaskScore> scores(tasks.size());
  for (TaskScore& score : scores) score.Tally.assign(tally.size(), 0.0);
  const std::int64_t photons = std::max<std::int64_t>(1, request.Photons);
  for (int round = 0; round < Rounds; ++round)
  {
    parallelFor(0, static_cast<int>(tasks.size()), [&](int begin, int end) {
      for (int k = begin; k < end; ++k)
      {
        const int t = tasks[static_cast<std::size_t>(k)];
        const int m = t % ScatteredLightNodes, part = round * TasksPerNode + t / ScatteredLightNodes;
        const std::int64_t first = photons * part / (Rounds * TasksPerNode);
        const std::int64_t last = photons * (part + 1) / (Rounds * TasksPerNode);
        for (std::int64_t i = first; i < last; ++i) nodes[m].trace(photons * m + i, photons, scores[k]);
      }
    });
    if (keepGoing && !keepGoing(double(round + 1) / Rounds))
    {
      return std::nullopt;
    }
  }
  std::vector<double> packed;
  packed.reserve(tasks.size() * (PackedPowers + tally.size()));
  for (const TaskScore& score : scores) packScore(score, packed);
  return packed;
}

ScatteredLight scatteredLightFromShares(const ScatteringMedium& medium, const ScatteredLightRequest& request,
  const std::vector<std::vector<double>>& shares)
{
  if (shares.empty())
  {
    throw std::invalid_argument("The scattered light needs the scores of one share or more, got none.");
  }
  const TallyGrid tally(medium.Geometry);
  const int count = static_cast<int>(shares.size());
  std::vector<TaskScore> scores(ScatteredLightNodes * TasksPerNode);
  for (int s = 0; s < count; ++s)
  {
    const std::vector<int> tasks = tasksOfShare(s, count);
    if (shares[s].size() != tasks.size() * (PackedPowers + tally.size()))
    {
      throw std::invalid_argument("The scattered light's share " + std::to_string(s) + " of " +
        std::to_string(count) + " holds " + std::to_string(shares[s].size()) + " values, not the " +
        std::to_string(tasks.size() * (PackedPowers + tally.size())) + " of its tasks' tallies.");
    }
    const double* packed = shares[s].data();
    for (const int t : tasks) packed = unpackScore(packed, tally.size(), scores[t]);
  }
  ScatteredLight field;
  field.Voxels = medium.Scattering.size();
  if (!medium.NodeVolumes.empty() && medium.NodeVolumes.size() != tally.size())
  {
    throw std::invalid_argument("The medium's NodeVolumes hold " + std::to_string(medium.NodeVolumes.size()) +
      " values, not the tally grid's " + std::to_string(tally.size()) + ".");
  }
  field.NodeVolumes = medium.NodeVolumes.empty() ? insideVolumes(medium.Geometry, tally) : medium.NodeVolumes;
  field.Scales = request.NodeScales;
  std::array<std::vector<double>, ScatteredLightNodes>& tallies = field.NodeTallies;
  for (auto& t : tallies) t.assign(tally.size(), 0.0);
  for (std::size_t t = 0; t < scores.size(); ++t)
  {
    const TaskScore& score = scores[t];
    std::transform(score.Tally.begin(), score.Tally.end(), tallies[t % ScatteredLightNodes].begin(),
      tallies[t % ScatteredLightNodes].begin(), std::plus<>());
    field.Entered += score.Entered;
    field.Escaped += score.Escaped;
    field.Absorbed += score.Absorbed;
    field.GivenUp += score.GivenUp;
  }
  if (field.GivenUp > ReportedShortfall * field.Entered)
  {
    field.Warning = "The every-order scattering solve gave up " +
      std::to_string(100.0 * field.GivenUp / field.Entered) + "% of the light entering the stone after " +
      std::to_string(request.CollisionBudget) + " collisions per photon: the volume's optical depth is beyond its budget, "
      "and the scattered light is short by that share.";
  }
  return field;
}

void ScatteredLight::meanRadiance(
  const ScatteringMedium& medium, std::size_t first, std::size_t count, Values* into) const
{
  if (medium.Scattering.size() != this->Voxels || first > this->Voxels || count > this->Voxels - first)
  {
    throw std::invalid_argument("The scattered light of " + std::to_string(this->Voxels) +
      " voxels was asked for voxels " + std::to_string(first) + " to " + std::to_string(first + count) +
      " of a medium of " + std::to_string(medium.Scattering.size()) + ".");
  }
  const TallyGrid tally(medium.Geometry);
  const VolumeGeometry& g = medium.Geometry;
  const glm::ivec3 dims = g.dimensions();
  const std::size_t row = static_cast<std::size_t>(dims.x), layer = row * static_cast<std::size_t>(dims.y);
  const int blocks = static_cast<int>(std::min<std::size_t>(count, 256));
  parallelFor(0, blocks, [&](int begin, int end) {
    for (std::size_t v = first + count * begin / blocks; v < first + count * end / blocks; ++v)
    {
      Values& values = into[v - first];
      values = {};
      if (!(medium.Scattering[v] > 0))
      {
        continue;
      }
      const glm::ivec3 voxel(static_cast<int>(v % row), static_cast<int>(v % layer / row), static_cast<int>(v / layer));
      double volume = 0;
      std::array<double, ScatteredLightNodes> sums{};
      tally.forEachNodeOfVoxel(voxel, [&](std::size_t n, double w) {
        volume += w * this->NodeVolumes[n];
        for (int m = 0; m < ScatteredLightNodes; ++m) sums[m] += w * this->NodeTallies[m][n];
      });
      for (int m = 0; m < ScatteredLightNodes && volume > 0; ++m)
      {
        values[m] = static_cast<float>(sums[m] / volume / (4.0 * Pi * this->Scales[m]));
      }
    }
  });
}

std::vector<ScatteredLight::GridNode> ScatteredLight::gridNodes() const
{
  std::vector<GridNode> nodes(this->NodeVolumes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
  {
    for (int m = 0; m < ScatteredLightNodes; ++m)
    {
      nodes[n].Tally[m] = static_cast<float>(this->NodeTallies[m][n] / (4.0 * Pi * this->Scales[m]));
    }
    nodes[n].Volume = static_cast<float>(this->NodeVolumes[n]);
  }
  return nodes;
}

std::optional<ScatteredLight> solveScatteredLight(const ScatteringMedium& medium,
  const ScatteredLightRequest& request, const std::function<bool(double)>& keepGoing)
{
  std::optional<std::vector<double>> scores = traceScatteredLightShare(medium, request, 0, 1, keepGoing);
  if (!scores)
  {
    return std::nullopt;
  }
  return scatteredLightFromShares(medium, request, { std::move(*scores) });
}

} // namespace opal
