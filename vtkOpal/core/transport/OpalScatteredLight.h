// Every order of scattering beyond the first (docs/design.md §3.10): the
// light inside the stone that has scattered at least once, as a field per
// light. With the isotropic phase the light a point scatters does not depend
// on the view, so the field is solved once per light, volume and optics, and
// the view march reads it beside the direct light field.
//
// The solve is Monte Carlo photon tracing into a grid: photons leave the
// point light, enter the stone along the straight line (the paper's light
// path, carrying 1 - F of the entry), fly freely through the voxels'
// extinction (delta tracking), scatter isotropically, are reflected inside
// by Fresnel's law (totally beyond the critical angle) or leave; the direct,
// never-scattered beam leaves where it meets the surface, as the direct
// light field has it. Every flight point of a photon that has scattered
// scores its track-length (collision) estimate of the fluence on a coarse
// tally grid, and the field at a voxel is the kernel estimate of the tally
// grid's eight nodes around it.
#pragma once

#include "OpalVolumeGeometry.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace opal
{

// The field's spectral nodes: ScatteredLightNodes values of s = (550/lambda)^4,
// evenly spaced in sqrt(s) from the wavelength table's longest wavelength to
// its shortest.
constexpr int ScatteredLightNodes = 4;

// The medium as the render's march sees it (skin cells filled): per voxel the
// scattering at 550 nm and, if anything absorbs, the (coloured, grey)
// absorption at 550 nm; the coloured part scales as (550/lambda)^p.
struct ScatteringMedium
{
  VolumeGeometry Geometry;
  std::vector<float> Scattering;
  std::vector<glm::vec2> Absorption; // empty: nothing absorbs
  float AbsorptionExponent = 0.0f;
  // The tally nodes' inside volumes (scatteredLightNodeVolumes(Geometry)):
  // they do not depend on the light, so a caller that solves for several
  // lights keeps them here; empty, each solve computes them.
  std::vector<double> NodeVolumes;
};

// The tally grid's longest side in cells (0.3-0.4 mm at the paper's scale):
// the scattered field varies over a mean free path (0.7-4 mm in the paper's
// body) but falls faster near the surface, where a coarser kernel's one-sided
// average brightened it (32 cells: the mean +0.8 to +1.6% against the tracer,
// 64: -0.3 to +0.5%, at the price of more noise per pixel; docs/design.md §3.10).
constexpr int ScatteredLightCellsAlongLongestSide = 64;

// The coarse tally grid the field is held on (docs/design.md §3.10): its
// nodes per axis (at most ScatteredLightCellsAlongLongestSide + 1, and no
// more than the voxels), node i of an axis at voxel i x Stride.
struct ScatteredLightGrid
{
  glm::ivec3 Nodes{ 1 };
  int Stride = 1;
  std::size_t size() const { return static_cast<std::size_t>(this->Nodes.x) * this->Nodes.y * this->Nodes.z; }
};
ScatteredLightGrid scatteredLightGrid(const VolumeGeometry& geometry);
ScatteredLightGrid scatteredLightGrid(const glm::ivec3& voxelDimensions);

// The inside volume each tally node's trilinear weights give it (the kernel
// estimate's denominators, docs/design.md §3.10), of the geometry alone.
std::vector<double> scatteredLightNodeVolumes(const VolumeGeometry& geometry);

struct ScatteredLightRequest
{
  glm::dvec3 Light{ 0.0 };   // in the model's frame, mm
  double LightStrength = 1;  // intensity: |light - apex|^2 makes the apex's irradiance 1
  double RefractiveIndex = 1.45;
  std::array<double, ScatteredLightNodes> NodeScales{}; // s of each node
  std::int64_t Photons = 1 << 14;                       // per node
  std::uint64_t Seed = 1;
  // Real collisions one photon may make before the solve gives it up: far
  // beyond any stone the model builds (fig12's bluest node: ~10^2 on average).
  int CollisionBudget = 100000;
};

// Per voxel and node: the mean radiance of the scattered light, fluence /
// (4 pi), divided by the node's s (nearly constant in s where the stone is
// thin, so the march's interpolation over the nodes is smooth; §3.10). Zero
// in voxels without scattering. Held as the solve's tallies on the coarse
// grid, never per voxel: meanRadiance gives any voxels' values from them,
// and the device writes the same from gridNodes (the light pass's
// LightPassScatteredField).
struct ScatteredLight
{
  using Values = std::array<float, ScatteredLightNodes>;
  // The values of `count` voxels of `medium` (the medium solved) from voxel
  // `first` on (x fastest) into `into`, over the threads: each the kernel
  // estimate of the eight tally nodes around it. Throws std::invalid_argument
  // for another medium's size or voxels beyond it.
  // The host's reference in double precision (TestOpalScatteredLight holds
  // the device's evaluation from gridNodes to it).
  void meanRadiance(const ScatteringMedium& medium, std::size_t first, std::size_t count, Values* into) const;

  // A node of the tally grid (scatteredLightGrid), in single precision as
  // the device evaluates the field from them: its tally at each spectral
  // node over 4 pi s, and its inside volume. A voxel's value is
  // sum(w Tally) / sum(w Volume) over the eight nodes around it, trilinear
  // weights w, as meanRadiance gives it.
  struct GridNode
  {
    Values Tally{};
    float Volume = 0;
  };
  std::vector<GridNode> gridNodes() const;

  // Of the power that entered the stone (sum over nodes): what left, what was
  // absorbed, and what the collision budget gave up (the solve's shortfall).
  double Entered = 0, Escaped = 0, Absorbed = 0, GivenUp = 0;
  // Empty, or a sentence saying the solve ran out of its budget and by how much.
  std::string Warning;

private:
  friend ScatteredLight scatteredLightFromShares(const ScatteringMedium& medium,
    const ScatteredLightRequest& request, const std::vector<std::vector<double>>& shares);
  std::size_t Voxels = 0;
  std::vector<double> NodeVolumes; // the inside volume each tally node's weights give it
  std::array<std::vector<double>, ScatteredLightNodes> NodeTallies;
  std::array<double, ScatteredLightNodes> Scales{};
};

// The nodes' s for a wavelength table spanning [shortest, longest] nm.
std::array<double, ScatteredLightNodes> scatteredLightScales(double shortestNm, double longestNm);

// Solves the field; nullopt if `keepGoing` (called with the fraction done)
// returned false. Deterministic for a seed, whatever the thread count.
std::optional<ScatteredLight> solveScatteredLight(const ScatteringMedium& medium,
  const ScatteredLightRequest& request, const std::function<bool(double)>& keepGoing);

// The solve shared by several processes (docs/design.md §8.1): its photon
// tasks are dealt to `shares` shares, and share `share` traces its own and
// returns their scores packed (nullopt if `keepGoing` returned false). The
// field from every share's scores, in share order, equals solveScatteredLight's
// bit for bit: each task traces the same photons, and the tasks are summed in
// the same order. Throws std::invalid_argument for a share that does not exist,
// no scores, or scores of the wrong size.
std::optional<std::vector<double>> traceScatteredLightShare(const ScatteringMedium& medium,
  const ScatteredLightRequest& request, int share, int shares, const std::function<bool(double)>& keepGoing);
ScatteredLight scatteredLightFromShares(const ScatteringMedium& medium, const ScatteredLightRequest& request,
  const std::vector<std::vector<double>>& shares);

} // namespace opal
