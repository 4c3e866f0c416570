#include "OpalDiameterField.h"

#include "OpalRandom.h"

#include <cmath>

namespace opal
{

DiameterField::DiameterField(const ModelParameters& p)
  : Seed(p.Seed)
  , Range(p.ScatteringDiameterRange)
  , CorrelationLength(p.DiameterCorrelationLength)
  , VoxelGrid(Grid::fromParameters(p))
{
  for (int a = 0; a < 3; ++a)
  {
    this->Corner[a] = this->VoxelGrid.Origin[a] - this->VoxelGrid.Spacing[a] / 2;
  }
}

double DiameterField::at(int i, int j, int k) const
{
  const double u = this->unitValue(this->VoxelGrid.position(i, j, k), this->VoxelGrid.linearIndex(i, j, k));
  return this->Range[0] + (this->Range[1] - this->Range[0]) * u;
}

double DiameterField::latticeValue(std::int64_t ix, std::int64_t iy, std::int64_t iz) const
{
  const std::uint64_t node =
    mix64(mix64(static_cast<std::uint64_t>(ix)) ^ static_cast<std::uint64_t>(iy)) ^ static_cast<std::uint64_t>(iz);
  return unitFromHash(hashCounter(this->Seed, RandomStream::DiameterField, node));
}

double DiameterField::unitValue(const std::array<double, 3>& position, std::int64_t globalIndex) const
{
  if (this->CorrelationLength <= 0)
  {
    return unitFromHash(
      hashCounter(this->Seed, RandomStream::ScatteringDiameter, static_cast<std::uint64_t>(globalIndex)));
  }
  std::int64_t node[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    const double g = (position[a] - this->Corner[a]) / this->CorrelationLength;
    const double cell = std::floor(g);
    node[a] = static_cast<std::int64_t>(cell);
    f[a] = g - cell;
  }
  double value = 0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
    const double weight = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
    value += weight * this->latticeValue(node[0] + dx, node[1] + dy, node[2] + dz);
  }
  return value;
}

} // namespace opal
