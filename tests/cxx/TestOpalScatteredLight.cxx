// The every-order solve on its own (OpalScatteredLight, docs/design.md
// §3.10), on the host: energy conservation (without absorption what enters
// the stone leaves it, photon by photon; with absorption what enters leaves
// or is absorbed, within the Monte Carlo error of the roulette), the
// refractive boundary keeping light inside (total internal reflection: a
// stone of index 1.45 holds more scattered light than an index-matched one),
// determinism for a seed, the nodes' volumes kept with the medium giving the
// same field, any range of voxels equal to the whole field there, the
// device's single-precision evaluation from the grid's nodes equal to
// meanRadiance within float rounding, no voxel orders of magnitude above the
// field, the solve shared by processes equal to one process's bit for bit
// (docs/design.md §8.1), and an optical depth beyond the budget: a warning
// naming the shortfall and a finite field, never NaN.
#include "OpalEllipsoidScene.h"
#include "OpalScatteredLight.h"
#include "OpalTestHarness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
opal::ScatteringMedium mediumOf(const opal::RenderVolume& volume)
{
  opal::ScatteringMedium medium;
  medium.Geometry = opal::VolumeGeometry(volume);
  medium.Scattering.assign(volume.ScatteringCoefficient, volume.ScatteringCoefficient + volume.voxelCount());
  return medium;
}

opal::ScatteredLightRequest requestFor(const opal::ScatteringMedium& medium, double refractiveIndex, int photons)
{
  opal::ScatteredLightRequest request;
  request.Light = { 0.0, 60.0, 0.0 };
  const glm::dvec3 toApex = request.Light - medium.Geometry.apex();
  request.LightStrength = glm::dot(toApex, toApex);
  request.RefractiveIndex = refractiveIndex;
  request.NodeScales = opal::scatteredLightScales(380.0, 780.0);
  request.Photons = photons;
  return request;
}

// The whole field, every voxel of `medium` (the medium solved).
std::vector<opal::ScatteredLight::Values> valuesOf(const opal::ScatteredLight& field, const opal::ScatteringMedium& medium)
{
  std::vector<opal::ScatteredLight::Values> values(medium.Scattering.size());
  field.meanRadiance(medium, 0, values.size(), values.data());
  return values;
}

// The field's mean over the voxels, of each node.
std::array<double, opal::ScatteredLightNodes> fieldMeans(
  const opal::ScatteredLight& field, const opal::ScatteringMedium& medium)
{
  std::array<double, opal::ScatteredLightNodes> sums{};
  const std::vector<opal::ScatteredLight::Values> all = valuesOf(field, medium);
  for (const auto& values : all)
    for (int m = 0; m < opal::ScatteredLightNodes; ++m)
      sums[m] += values[static_cast<std::size_t>(m)];
  for (double& sum : sums)
    sum /= static_cast<double>(all.size());
  return sums;
}

// The solve dealt to `shares` shares, each traced on its own and the scores
// put together, as the ranks of an MPI render do.
opal::ScatteredLight sharedSolve(
  const opal::ScatteringMedium& medium, const opal::ScatteredLightRequest& request, int shares)
{
  std::vector<std::vector<double>> scores;
  for (int share = 0; share < shares; ++share)
  {
    scores.push_back(*opal::traceScatteredLightShare(medium, request, share, shares, nullptr));
  }
  return opal::scatteredLightFromShares(medium, request, scores);
}

template <typename Work>
bool refuses(Work&& work, const std::string& naming)
{
  try
  {
    work();
  }
  catch (const std::invalid_argument& e)
  {
    std::cout << "refused: " << e.what() << std::endl;
    return std::string(e.what()).find(naming) != std::string::npos;
  }
  return false;
}

// A voxel's value as the device evaluates it from the tally grid's nodes, in
// single precision: opal_scattered_light_grid.glsl's scatteredLightAt, its twin (keep them alike).
opal::ScatteredLight::Values deviceValue(const std::vector<opal::ScatteredLight::GridNode>& nodes,
  const opal::ScatteredLightGrid& grid, const glm::ivec3& cell)
{
  const glm::ivec3 c0 = glm::min(cell / grid.Stride, glm::max(grid.Nodes - 2, glm::ivec3(0)));
  const glm::vec3 f = glm::min(glm::vec3(cell - c0 * grid.Stride) / float(grid.Stride), 1.0f);
  glm::vec4 sums(0.0f);
  float volume = 0.0f;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::ivec3 n = glm::min(c0 + o, grid.Nodes - 1);
    const glm::vec3 w3 = glm::mix(1.0f - f, f, glm::vec3(o));
    const float w = w3.x * w3.y * w3.z;
    const opal::ScatteredLight::GridNode& node = nodes[static_cast<std::size_t>(n.x + grid.Nodes.x * (n.y + grid.Nodes.y * n.z))];
    sums += w * glm::vec4(node.Tally[0], node.Tally[1], node.Tally[2], node.Tally[3]);
    volume += w * node.Volume;
  }
  const glm::vec4 value = volume > 0.0f ? sums / volume : glm::vec4(0.0f);
  return { value.x, value.y, value.z, value.w };
}

// The largest difference, relative to the voxel's largest value, between
// meanRadiance and the device's single-precision evaluation from the nodes.
// The inside bits on a grid of 105 voxels (64 to a word: the last word part
// filled): each voxel's bit is its SurfaceDistance's sign (0 inside), by index
// and by position, and values whose last voxel's sign differs are refused.
bool insideBitsOfOddGrid()
{
  std::vector<float> distance(5 * 3 * 7);
  for (std::size_t v = 0; v < distance.size(); ++v)
  {
    distance[v] = static_cast<float>(static_cast<int>(v * 37 % 11) - 5);
  }
  distance.back() = -0.5f; // inside: a last bit left unset shows
  opal::RenderVolume volume;
  volume.Dimensions = { 5, 3, 7 };
  volume.Origin = { -1.0, 0.0, 2.0 };
  volume.Spacing = { 0.5, 0.25, 1.0 };
  volume.SurfaceDistance = distance.data();
  opal::VolumeGeometry geometry(volume, false);
  bool agrees = true;
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i)
      {
        const bool inside = distance[static_cast<std::size_t>(i + 5 * (j + 3 * k))] <= 0;
        const glm::dvec3 p = glm::dvec3(-1.0, 0.0, 2.0) + glm::dvec3(i, j, k) * glm::dvec3(0.5, 0.25, 1.0);
        agrees = agrees && geometry.insideVoxel(i, j, k) == inside && geometry.insideAt(p) == inside;
      }
  std::vector<float> lastFlipped = distance;
  lastFlipped.back() = lastFlipped.back() <= 0 ? 1.0f : -1.0f;
  geometry.setSurfaceDistance(distance);
  return agrees && refuses([&] { geometry.setSurfaceDistance(lastFlipped); }, "at voxel 104");
}

double largestDeviceDifference(const opal::ScatteredLight& field, const opal::ScatteringMedium& medium)
{
  const std::vector<opal::ScatteredLight::Values> exact = valuesOf(field, medium);
  const std::vector<opal::ScatteredLight::GridNode> nodes = field.gridNodes();
  const opal::ScatteredLightGrid grid = opal::scatteredLightGrid(medium.Geometry);
  const glm::ivec3 dims = medium.Geometry.dimensions();
  double largest = 0;
  for (std::size_t v = 0; v < exact.size(); ++v)
  {
    if (!(medium.Scattering[v] > 0)) continue;
    const glm::ivec3 cell(int(v % dims.x), int(v / dims.x % dims.y), int(v / (std::size_t(dims.x) * dims.y)));
    const opal::ScatteredLight::Values device = deviceValue(nodes, grid, cell);
    const float scale = *std::max_element(exact[v].begin(), exact[v].end());
    for (int m = 0; m < opal::ScatteredLightNodes; ++m)
    {
      double d = std::fabs(double(device[m]) - exact[v][m]) / std::max(scale, 1e-30f);
      largest = std::max(largest, d);
    }
  }
  return largest;
}

// The field's largest value over its mean, of the scattering voxels and
// the reddest node (the least scattered light varies the least).
double largestOverMean(const opal::ScatteredLight& field, const opal::ScatteringMedium& medium)
{
  const std::vector<opal::ScatteredLight::Values> all = valuesOf(field, medium);
  double largest = 0, sum = 0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < all.size(); ++v)
  {
    if (!(medium.Scattering[v] > 0)) continue;
    largest = std::max(largest, double(all[v][0]));
    sum += all[v][0];
    ++count;
  }
  return largest / (sum / double(std::max<std::size_t>(count, 1)));
}

bool allFinite(const opal::ScatteredLight& field, const opal::ScatteringMedium& medium)
{
  for (const auto& values : valuesOf(field, medium))
    for (const float v : values)
      if (!std::isfinite(v) || v < 0)
        return false;
  return true;
}
// Clear of absorption: every photon that entered leaves (no roulette, no
// budget reached); the field is deterministic, kept nodes' volumes and
// ranges of voxels give the same values, the device's evaluation agrees, and
// a solve shared by 2, 3, 5 and 20 processes equals one process's. Returns it.
opal::ScatteredLight checkClearField(const opal::ScatteringMedium& medium)
{
  const auto clear = opal::solveScatteredLight(medium, requestFor(medium, 1.45, 4096), nullptr);
  OPAL_CHECK(clear && clear->Warning.empty() && clear->GivenUp == 0, "the paper's body is within the budget");
  OPAL_CHECK(std::fabs(clear->Escaped / clear->Entered - 1) < 1e-9, "without absorption what enters leaves");
  OPAL_CHECK(allFinite(*clear, medium), "the field is finite and not negative");
  const auto again = opal::solveScatteredLight(medium, requestFor(medium, 1.45, 4096), nullptr);
  const std::vector<opal::ScatteredLight::Values> clearValues = valuesOf(*clear, medium);
  OPAL_CHECK(valuesOf(*again, medium) == clearValues, "the same seed gives the same field");
  // The nodes' volumes kept with the medium (as a session solving for several lights keeps them): the same field.
  opal::ScatteringMedium kept = medium;
  kept.NodeVolumes = opal::scatteredLightNodeVolumes(kept.Geometry);
  const auto withKept = opal::solveScatteredLight(kept, requestFor(kept, 1.45, 4096), nullptr);
  OPAL_CHECK(valuesOf(*withKept, kept) == clearValues, "a solve with the nodes' volumes kept gives the same field");
  kept.NodeVolumes.pop_back();
  OPAL_CHECK(refuses([&] { opal::solveScatteredLight(kept, requestFor(kept, 1.45, 64), nullptr); }, "NodeVolumes"),
    "nodes' volumes of the wrong size are refused");
  const double peak = largestOverMean(*clear, medium);
  std::cout << "the field's largest value over its mean: " << peak << std::endl;
  // The hottest voxels, the top skin under the light, are ~60 times the mean; a node's inside volume of
  // rounding noise (weights from positions, not indices) once made voxels beside it 10^14 times their neighbours.
  OPAL_CHECK(peak < 100, "no voxel's value stands out of the field by orders of magnitude");
  // The device's evaluation from the nodes in single precision: meanRadiance within float rounding.
  const double deviceDifference = largestDeviceDifference(*clear, medium);
  std::cout << "the device's evaluation against meanRadiance: largest relative difference " << deviceDifference << std::endl;
  OPAL_CHECK(deviceDifference < 1e-5, "the grid's nodes give the device meanRadiance's values within float rounding");
  // Any voxels on their own: the same values.
  const std::size_t first = clearValues.size() / 3, count = clearValues.size() / 4 + 5;
  std::vector<opal::ScatteredLight::Values> part(count);
  clear->meanRadiance(medium, first, count, part.data());
  OPAL_CHECK(std::equal(part.begin(), part.end(), clearValues.begin() + static_cast<std::ptrdiff_t>(first)),
    "the values of a range of voxels equal the whole field's there");
  OPAL_CHECK(refuses([&] { clear->meanRadiance(medium, clearValues.size() - 1, 2, part.data()); }, "asked for voxels"),
    "voxels beyond the medium are refused");
  // Shared by 2, 3 and 5 processes, and by more processes than the solve has tasks: the same field.
  for (const int shares : { 2, 3, 5, 20 })
  {
    const opal::ScatteredLight shared = sharedSolve(medium, requestFor(medium, 1.45, 4096), shares);
    OPAL_CHECK(valuesOf(shared, medium) == clearValues && shared.Escaped == clear->Escaped,
      "a solve shared by " + std::to_string(shares) + " equals one process's bit for bit");
  }
  return *clear;
}

// The render session's geometry: the inside bits and the apex, SurfaceDistance given back (read from
// the device) when a solve needs it: the same field. Values whose signs disagree (a round read from
// the wrong place) are refused; without them surfaceDistance throws.
void checkGeometryGivenBack(
  const opal::RenderVolume& volume, const opal::ScatteringMedium& medium, const opal::ScatteredLight& clear)
{
  opal::ScatteringMedium givenBack = medium;
  givenBack.Geometry = opal::VolumeGeometry(volume, false);
  bool insideAgrees = !givenBack.Geometry.insideAt(medium.Geometry.boxHigh() + 1.0);
  const glm::ivec3 dims = medium.Geometry.dimensions();
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
      {
        const glm::dvec3 p = medium.Geometry.origin() + glm::dvec3(i, j, k) * medium.Geometry.spacing();
        const std::size_t v = static_cast<std::size_t>(i + dims.x * (j + dims.y * k));
        insideAgrees = insideAgrees && givenBack.Geometry.insideAt(p) == (volume.SurfaceDistance[v] <= 0);
      }
  bool throwsWithout = false;
  try
  {
    givenBack.Geometry.surfaceDistance(medium.Geometry.apex());
  }
  catch (const std::logic_error&)
  {
    throwsWithout = true;
  }
  OPAL_CHECK(insideAgrees && throwsWithout && givenBack.Geometry.apex() == medium.Geometry.apex(),
    "a geometry without SurfaceDistance keeps each voxel's inside and the apex, and asks for the rest");
  OPAL_CHECK(insideBitsOfOddGrid(), "the inside bits of 105 voxels are their signs, the last word's too");
  std::vector<float> distance(volume.SurfaceDistance, volume.SurfaceDistance + volume.voxelCount());
  std::vector<float> shifted(distance.begin() + 1, distance.end());
  shifted.push_back(distance.back());
  OPAL_CHECK(refuses([&] { givenBack.Geometry.setSurfaceDistance(shifted); }, "disagrees"),
    "SurfaceDistance given back one voxel off is refused");
  givenBack.Geometry.setSurfaceDistance(distance);
  const auto fromGivenBack = opal::solveScatteredLight(givenBack, requestFor(givenBack, 1.45, 4096), nullptr);
  OPAL_CHECK(valuesOf(*fromGivenBack, givenBack) == valuesOf(clear, medium), "SurfaceDistance given back: the same field");
}

// Absorbing: grey 0.1/mm everywhere and 2/mm in the lowest millimetre (a
// backing): what enters leaves or is absorbed, and the field dims.
void checkAbsorbingBody(
  opal::ScatteringMedium medium, const std::array<double, opal::ScatteredLightNodes>& clearMeans)
{
  const opal::VolumeGeometry& g = medium.Geometry;
  medium.Absorption.resize(medium.Scattering.size());
  for (std::size_t i = 0; i < medium.Absorption.size(); ++i)
  {
    const std::size_t row = i / static_cast<std::size_t>(g.dimensions().x);
    const int j = static_cast<int>(row % static_cast<std::size_t>(g.dimensions().y));
    medium.Absorption[i] = glm::vec2(0.0f, g.origin().y + j * g.spacing().y < 1.0 ? 2.0f : 0.1f);
  }
  const auto absorbing = opal::solveScatteredLight(medium, requestFor(medium, 1.45, 4096), nullptr);
  const double balance = (absorbing->Escaped + absorbing->Absorbed) / absorbing->Entered - 1;
  std::cout << "absorbing: escaped " << absorbing->Escaped / absorbing->Entered << ", absorbed "
            << absorbing->Absorbed / absorbing->Entered << ", balance " << balance << std::endl;
  OPAL_CHECK(std::fabs(balance) < 0.01, "with absorption what enters leaves or is absorbed (roulette: within 1%)");
  OPAL_CHECK(absorbing->Absorbed > 0.1 * absorbing->Entered, "the absorption and the backing take their share");
  OPAL_CHECK(fieldMeans(*absorbing, medium)[0] < clearMeans[0], "absorption dims the scattered light");
}

// An optical depth beyond the budget: said, and the field it has is finite;
// cancelled: no field.
void checkBudgetAndCancel(opal::ScatteringMedium medium)
{
  medium.Absorption.clear();
  for (float& mu : medium.Scattering)
    mu = 2000.0f;
  opal::ScatteredLightRequest deep = requestFor(medium, 1.45, 256);
  deep.CollisionBudget = 1000;
  const auto opaque = opal::solveScatteredLight(medium, deep, nullptr);
  std::cout << "opaque: " << opaque->Warning << std::endl;
  OPAL_CHECK(!opaque->Warning.empty() && opaque->Warning.find("budget") != std::string::npos,
    "a solve beyond its budget says so");
  OPAL_CHECK(allFinite(*opaque, medium), "and gives a finite field");
  OPAL_CHECK(!opal::solveScatteredLight(medium, requestFor(medium, 1.0, 64), [](double) { return false; }),
    "a cancelled solve gives nothing");
}
} // namespace

int TestOpalScatteredLight(int, char*[])
{
  opaltest::EllipsoidScene scene;
  const opal::RenderVolume volume = scene.build();
  const opal::ScatteringMedium medium = mediumOf(volume);
  const opal::ScatteredLight clear = checkClearField(medium);
  checkGeometryGivenBack(volume, medium, clear);

  const opal::ScatteredLightRequest small = requestFor(medium, 1.45, 64);
  OPAL_CHECK(refuses([&] { opal::traceScatteredLightShare(medium, small, 2, 2, nullptr); }, "share 2 of 2"),
    "a share that does not exist is refused");
  std::vector<std::vector<double>> oneMissing{ *opal::traceScatteredLightShare(medium, small, 0, 2, nullptr), {} };
  OPAL_CHECK(refuses([&] { opal::scatteredLightFromShares(medium, small, oneMissing); }, "share 1 of 2 holds 0"),
    "scores of the wrong size are refused, naming the share");

  // Total internal reflection keeps the scattered light inside longer.
  const auto matched = opal::solveScatteredLight(medium, requestFor(medium, 1.0, 4096), nullptr);
  const auto clearMeans = fieldMeans(clear, medium), matchedMeans = fieldMeans(*matched, medium);
  for (int m = 0; m < opal::ScatteredLightNodes; ++m)
  {
    std::cout << "node " << m << ": field mean " << clearMeans[m] << " at index 1.45, "
              << matchedMeans[m] << " index-matched" << std::endl;
    OPAL_CHECK(clearMeans[m] > 1.2 * matchedMeans[m], "a refracting boundary holds scattered light in");
  }
  checkAbsorbingBody(medium, clearMeans);
  checkBudgetAndCancel(medium);
  return opaltest::finish("TestOpalScatteredLight");
}
