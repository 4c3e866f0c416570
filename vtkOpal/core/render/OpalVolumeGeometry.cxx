#include "OpalVolumeGeometry.h"

#include "OpalParallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace opal
{

VolumeGeometry::VolumeGeometry(const RenderVolume& volume, bool keepSurfaceDistance)
  : Dimensions(volume.Dimensions[0], volume.Dimensions[1], volume.Dimensions[2])
  , Origin(volume.Origin[0], volume.Origin[1], volume.Origin[2])
  , Spacing(volume.Spacing[0], volume.Spacing[1], volume.Spacing[2])
{
  this->takeInsideBits(volume.SurfaceDistance);
  this->Apex = this->apexOf(volume.SurfaceDistance);
  if (keepSurfaceDistance)
  {
    this->SurfaceDistance.assign(volume.SurfaceDistance, volume.SurfaceDistance + volume.voxelCount());
  }
}

void VolumeGeometry::takeInsideBits(const float* distance)
{
  const std::size_t voxels = this->voxelCount();
  this->InsideBits.assign((voxels + 63) / 64, 0);
  parallelFor(0, static_cast<int>(this->InsideBits.size()), [&](int from, int to) {
    for (std::size_t w = static_cast<std::size_t>(from); w < static_cast<std::size_t>(to); ++w)
    {
      std::uint64_t bits = 0;
      for (std::size_t v = 64 * w; v < std::min(voxels, 64 * w + 64); ++v)
      {
        bits |= static_cast<std::uint64_t>(distance[v] <= 0) << (v % 64);
      }
      this->InsideBits[w] = bits;
    }
  });
}

void VolumeGeometry::setSurfaceDistance(std::vector<float> values)
{
  if (values.size() != this->voxelCount())
  {
    throw std::invalid_argument("SurfaceDistance has " + std::to_string(values.size()) + " values for " +
      std::to_string(this->voxelCount()) + " voxels");
  }
  // The values given back (read from a device) must be those the inside bits
  // were taken from: a round read at the wrong place disagrees at the surface.
  for (std::size_t v = 0; v < values.size(); ++v)
  {
    if ((values[v] <= 0) != this->insideBit(v))
    {
      throw std::invalid_argument("SurfaceDistance given back disagrees with the volume's at voxel " +
        std::to_string(v) + " (" + std::to_string(values[v]) + ")");
    }
  }
  this->SurfaceDistance = std::move(values);
}

std::size_t VolumeGeometry::indexOf(int i, int j, int k) const
{
  const std::size_t nx = static_cast<std::size_t>(this->Dimensions.x);
  const std::size_t ny = static_cast<std::size_t>(this->Dimensions.y);
  return static_cast<std::size_t>(i) + nx * (static_cast<std::size_t>(j) + ny * static_cast<std::size_t>(k));
}

std::size_t VolumeGeometry::voxelCount() const
{
  return static_cast<std::size_t>(this->Dimensions.x) * static_cast<std::size_t>(this->Dimensions.y) *
    static_cast<std::size_t>(this->Dimensions.z);
}

bool VolumeGeometry::insideAt(const glm::dvec3& p) const
{
  int c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = static_cast<int>(std::floor((p[a] - this->Origin[a]) / this->Spacing[a] + 0.5));
    if (c[a] < 0 || c[a] >= this->Dimensions[a])
    {
      return false;
    }
  }
  return this->insideVoxel(c[0], c[1], c[2]);
}

double VolumeGeometry::surfaceDistance(const glm::dvec3& p) const
{
  if (!this->hasSurfaceDistance())
  {
    throw std::logic_error("the volume's geometry holds no SurfaceDistance");
  }
  // As the shaders' trilinearSurfaceDistance: up to the grid's box (half a
  // cell beyond the outermost centres) the outermost cells continue linearly.
  const glm::dvec3 g =
    glm::clamp((p - this->Origin) / this->Spacing, glm::dvec3(-0.5), glm::dvec3(this->Dimensions) - 0.5);
  const glm::ivec3 c0 = glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), glm::max(this->Dimensions - 2, glm::ivec3(0)));
  const glm::ivec3 c1 = glm::min(c0 + 1, this->Dimensions - 1);
  const glm::dvec3 f = g - glm::dvec3(c0);
  const auto along = [&](int j, int k) {
    return glm::mix(this->distanceAt(c0.x, j, k), this->distanceAt(c1.x, j, k), f.x);
  };
  return glm::mix(glm::mix(along(c0.y, c0.z), along(c1.y, c0.z), f.y),
    glm::mix(along(c0.y, c1.z), along(c1.y, c1.z), f.y), f.z);
}

glm::dvec3 VolumeGeometry::surfaceNormal(const glm::dvec3& p) const
{
  glm::dvec3 gradient;
  for (int a = 0; a < 3; ++a)
  {
    glm::dvec3 step(0.0);
    step[a] = 0.5 * this->Spacing[a];
    gradient[a] = this->surfaceDistance(p + step) - this->surfaceDistance(p - step);
  }
  const double length = glm::length(gradient);
  return length > 0 ? gradient / length : glm::dvec3(0, 1, 0);
}

glm::dvec3 VolumeGeometry::boxLow() const
{
  return this->Origin - 0.5 * this->Spacing;
}

glm::dvec3 VolumeGeometry::boxHigh() const
{
  return this->boxLow() + glm::dvec3(this->Dimensions) * this->Spacing;
}

glm::dvec3 VolumeGeometry::apexOf(const float* distance) const
{
  const int i = this->Dimensions.x / 2, k = this->Dimensions.z / 2, ny = this->Dimensions.y;
  const double x = this->Origin.x + i * this->Spacing.x;
  const double z = this->Origin.z + k * this->Spacing.z;
  for (int j = ny - 1; j >= 0; --j)
  {
    const double here = distance[this->indexOf(i, j, k)];
    if (here <= 0)
    {
      const double y0 = this->Origin.y + j * this->Spacing.y;
      const double above = j + 1 < ny ? distance[this->indexOf(i, j + 1, k)] : here;
      // The zero between this voxel centre and the one above, else continued linearly.
      return above > here ? glm::dvec3(x, y0 + this->Spacing.y * (-here) / (above - here), z)
                          : glm::dvec3(x, y0 - here, z);
    }
  }
  return { x, this->Origin.y + (ny - 0.5) * this->Spacing.y, z };
}

bool VolumeGeometry::lightAboveGrid(const glm::dvec3& light) const
{
  const glm::dvec3 low = this->boxLow();
  const glm::dvec3 high = this->boxHigh();
  if (light.y < high.y + this->Spacing.y)
  {
    return false;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y, (corner & 4) ? high.z : low.z);
    const glm::dvec3 d = light - p;
    if (std::fabs(d.x) / d.y * this->Spacing.y > 0.5 * this->Spacing.x ||
      std::fabs(d.z) / d.y * this->Spacing.y > 0.5 * this->Spacing.z)
    {
      return false;
    }
  }
  return true;
}

double VolumeGeometry::smallestSpacing() const
{
  return std::min({ this->Spacing.x, this->Spacing.y, this->Spacing.z });
}

} // namespace opal
