// libFuzzer target: random, bounded parameter sets for the volume model, one
// value per component of every row of its table (OPAL_MODEL_PARAMETERS).
// Every set either fails validation with a message naming a parameter, or
// builds (domain layout and every voxel's fields) without a crash, a hang or
// a non-finite value. Sizes are bounded (at most 24^3 voxels, 40 domains, 50
// attempts) so each input runs in milliseconds.
#include "OpalDomainLayout.h"
#include "OpalGrid.h"
#include "OpalModelParameters.h"
#include "OpalVolumeFiller.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace
{
// Reads the fuzzer's bytes as parameters; when they run out, zeros.
class ByteReader
{
public:
  ByteReader(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  std::uint8_t byte() { return this->Offset < this->Size ? this->Data[this->Offset++] : 0; }
  int integer(int lo, int hi) { return lo + this->byte() % (hi - lo + 1); }
  // A real in [lo, hi], or now and then a raw double (NaN, infinity, huge).
  double real(double lo, double hi)
  {
    const std::uint8_t mode = this->byte();
    if (mode == 0xff)
    {
      double raw = 0;
      std::uint8_t bytes[8];
      for (auto& b : bytes)
      {
        b = this->byte();
      }
      std::memcpy(&raw, bytes, sizeof(raw));
      return raw;
    }
    return lo + (hi - lo) * (static_cast<double>(this->byte()) * 256 + mode) / 65535.0;
  }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Offset = 0;
};

// How far a size or count may go here, so each input runs in milliseconds.
double speedCap(const std::string& name)
{
  static const std::map<std::string, double> caps = { { "Dimensions", 24 }, { "DomainCount", 40 },
    { "DomainVertexRange", 12 }, { "VoronoiCellCount", 60 }, { "MaxPlacementAttempts", 50 }, { "Seed", 65535 } };
  const auto cap = caps.find(name);
  return cap == caps.end() ? std::numeric_limits<double>::max() : cap->second;
}

// Every row of the model parameters' table (OPAL_MODEL_PARAMETERS), each
// component from its range widened by a tenth on both sides (counts by one),
// sizes and counts capped for speed.
opal::ModelParameters decode(ByteReader& in)
{
  opal::ModelParameters p;
  for (const opal::ParameterRow<opal::ModelParameters>& row : opal::modelParameterRows())
  {
    const double hi = std::min(row.Max, speedCap(row.Name));
    std::vector<double> values(static_cast<std::size_t>(row.Components));
    for (double& v : values)
    {
      if (row.Type == opal::ParameterType::Double)
      {
        const double margin = (hi - row.Min) / 10;
        v = in.real(row.Min - margin, hi + margin);
      }
      else
      {
        v = in.integer(static_cast<int>(row.Min) - 1, static_cast<int>(hi) + 1);
      }
    }
    row.Set(p, values);
  }
  return p;
}

void require(bool condition, const char* what)
{
  if (!condition)
  {
    std::fprintf(stderr, "violated: %s\n", what);
    std::abort();
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  ByteReader in(data, size);
  const opal::ModelParameters p = decode(in);
  if (!opal::validate(p).empty())
  {
    return 0; // refused with a message: fine
  }
  const opal::DomainLayout layout = opal::DomainLayout::build(p);
  require(layout.hasCells() || layout.placedCount() <= p.DomainCount, "placed <= requested");
  const opal::Grid grid = opal::Grid::fromParameters(p);
  const std::size_t count = static_cast<std::size_t>(grid.voxelCount());
  std::vector<std::uint8_t> type(count);
  std::vector<float> diameter(count), normal(3 * count), lambdaMax(count), lambdaMin(count), scattering(count),
    distance(count);
  std::vector<std::int32_t> domain(count), cells(count);
  std::vector<float> absorption(count), exponent(count), orientation(4 * count);
  const bool absorbs = p.absorbs();
  const opal::VolumeFields fields{ type.data(), diameter.data(), normal.data(), domain.data(), lambdaMax.data(),
    lambdaMin.data(), scattering.data(), distance.data(), layout.hasCells() ? cells.data() : nullptr,
    absorbs ? absorption.data() : nullptr, absorbs ? exponent.data() : nullptr, orientation.data() };
  const std::array<int, 6> extent{ 0, p.Dimensions[0] - 1, 0, p.Dimensions[1] - 1, 0, p.Dimensions[2] - 1 };
  opal::VolumeFiller(p, layout).fill(extent, 0, p.Dimensions[2], fields);
  for (std::size_t i = 0; i < count; ++i)
  {
    require(type[i] <= 2, "VoxelType 0-2");
    require(std::isfinite(diameter[i]), "finite ParticleDiameter");
    require(std::isfinite(scattering[i]), "finite ScatteringCoefficient");
    require(std::isfinite(distance[i]), "finite SurfaceDistance");
    require(std::isfinite(absorption[i]) && absorption[i] >= 0, "finite AbsorptionCoefficient >= 0");
    require(std::isfinite(exponent[i]), "finite AbsorptionExponent");
    const float* q = &orientation[4 * i];
    const float norm = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    require(domain[i] >= 0 ? std::fabs(norm - 1.0f) < 1e-5f : norm == 0.0f, "LatticeOrientation unit in domains, 0 outside");
    require(std::isfinite(lambdaMax[i]) && std::isfinite(lambdaMin[i]), "finite Bragg wavelengths");
    require(domain[i] >= -1 && domain[i] < layout.placedCount(), "DomainId -1 or a placed domain");
    require(!layout.hasCells() || (cells[i] >= -1 && cells[i] < layout.cellCount()), "CellId -1 or a cell");
  }
  return 0;
}
