// Geometric questions the render asks of a volume on the host (docs/design.md
// §3): is a point inside the opal, where is its apex, can the light field be
// swept layer by layer.
#pragma once

#include "OpalRenderVolume.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace opal
{

// The grid's shape, which voxels lie inside the opal (a bit each), its apex,
// and a host copy of its SurfaceDistance field where kept.
class VolumeGeometry
{
public:
  VolumeGeometry() = default;
  // Without `keepSurfaceDistance` only the inside bits and the apex are kept
  // (the render session's, which reads SurfaceDistance back from the device
  // when a solve needs it: docs/design.md §3.10); setSurfaceDistance gives it,
  // refusing values whose signs disagree with the inside bits (or count).
  explicit VolumeGeometry(const RenderVolume& volume, bool keepSurfaceDistance = true);
  void setSurfaceDistance(std::vector<float> values);
  // Frees the host copy of SurfaceDistance (the inside bits and the apex stay).
  void releaseSurfaceDistance() { std::vector<float>().swap(this->SurfaceDistance); }
  bool hasSurfaceDistance() const { return !this->SurfaceDistance.empty(); }

  // Whether the voxel centre nearest a model-frame point lies inside the
  // opal (its SurfaceDistance <= 0); false outside the grid.
  bool insideAt(const glm::dvec3& p) const;
  // Whether voxel (i, j, k) of the grid lies inside (no bounds check).
  bool insideVoxel(int i, int j, int k) const { return this->insideBit(this->indexOf(i, j, k)); }

  // SurfaceDistance interpolated trilinearly over the voxel centres,
  // continued linearly to the grid's box (clamped beyond), the surface being
  // its zero as the march reads it. Needs SurfaceDistance (std::logic_error).
  double surfaceDistance(const glm::dvec3& p) const;

  // The outward unit normal there: the normalised central-difference
  // gradient of surfaceDistance, as the march takes it.
  glm::dvec3 surfaceNormal(const glm::dvec3& p) const;

  // The grid's box: from the first voxel's low corner to the last's high one.
  glm::dvec3 boxLow() const;
  glm::dvec3 boxHigh() const;

  // The opal's apex: the top of the surface over the grid's centre column
  // (SurfaceDistance crossing zero), or the top of the grid.
  const glm::dvec3& apex() const { return this->Apex; }

  // Whether the light sits above the grid steeply enough for the layer sweep:
  // every path to it rises through each layer moving at most half a voxel
  // sideways. (Each layer reads the one above bilinearly; at steeper slopes
  // the interpolation's error, summed over the layers of a long path through
  // the stone, brightened the far side by up to 10% against the converged
  // reference: the per-voxel march takes those lights.)
  bool lightAboveGrid(const glm::dvec3& light) const;

  double smallestSpacing() const;
  const glm::ivec3& dimensions() const { return this->Dimensions; }
  const glm::dvec3& origin() const { return this->Origin; }
  const glm::dvec3& spacing() const { return this->Spacing; }

private:
  std::size_t indexOf(int i, int j, int k) const;
  std::size_t voxelCount() const;
  bool insideBit(std::size_t v) const { return (this->InsideBits[v / 64] >> (v % 64)) & 1u; }
  void takeInsideBits(const float* distance);
  double distanceAt(int i, int j, int k) const { return this->SurfaceDistance[this->indexOf(i, j, k)]; }
  glm::dvec3 apexOf(const float* distance) const;

  glm::ivec3 Dimensions{ 0 };
  glm::dvec3 Origin{ 0.0 };
  glm::dvec3 Spacing{ 1.0 };
  // SurfaceDistance <= 0, a bit per voxel, 64 to a word: words are filled
  // in parallel, each by one thread (seconds of one loop at 10 um).
  std::vector<std::uint64_t> InsideBits;
  glm::dvec3 Apex{ 0.0 };
  std::vector<float> SurfaceDistance;
};

} // namespace opal
