// The scattering diameters' correlation length (docs/design.md §2.3): the
// value-noise field's autocorrelation at lags of L/2, L and 2L along each
// axis agrees with its closed form (2/3 - s^2 + s^3/2) / (2/3) (0 beyond
// s = 2), its mean is the range's middle, and length 0 is the paper's
// independent draw per voxel, bit for bit.
#include "OpalTestHarness.h"

#include "OpalDiameterField.h"
#include "OpalRandom.h"

#include <cmath>
#include <string>
#include <vector>

namespace
{
// Position-averaged autocorrelation of linear interpolation of white noise at
// lag s lattice spacings: the tent kernel's self-convolution over its value at 0.
double closedFormCorrelation(double s)
{
  s = std::fabs(s);
  if (s >= 2)
  {
    return 0;
  }
  const double tent = s <= 1 ? 2.0 / 3 - s * s + s * s * s / 2 : (2 - s) * (2 - s) * (2 - s) / 6;
  return tent / (2.0 / 3);
}

// Correlation of the field with itself shifted by `lag` mm along `axis`, over
// a block of points 0.1 L apart spanning about 24 L each way (~14000 lattice cells).
double sampledCorrelation(const opal::DiameterField& field, double length, int axis, double lag, double& mean)
{
  const int n = 240;
  const double step = 0.1 * length;
  double sum = 0, sumSquares = 0, sumProducts = 0;
  long long count = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; i += 4)
      {
        std::array<double, 3> x{ i * step, j * step, k * step };
        const double a = field.unitValue(x, 0);
        x[static_cast<std::size_t>(axis)] += lag;
        const double b = field.unitValue(x, 0);
        sum += a;
        sumSquares += a * a;
        sumProducts += a * b;
        ++count;
      }
  mean = sum / count;
  const double variance = sumSquares / count - mean * mean;
  return (sumProducts / count - mean * mean) / variance;
}
} // namespace

int TestOpalDiameterField(int, char*[])
{
  opal::ModelParameters p;
  p.DiameterCorrelationLength = 0.5;
  const opal::DiameterField field(p);
  // ~14000 independent lattice values: the estimate's standard error is about 0.01.
  for (int axis = 0; axis < 3; ++axis)
  {
    for (double s : { 0.5, 1.0, 2.0 })
    {
      double mean = 0;
      const double r = sampledCorrelation(field, 0.5, axis, s * 0.5, mean);
      const double expected = closedFormCorrelation(s);
      OPAL_CHECK(std::fabs(r - expected) < 0.05, "autocorrelation at " + std::to_string(s) + " L along axis " +
          std::to_string(axis) + ": " + std::to_string(r) + ", closed form " + std::to_string(expected));
      OPAL_CHECK(std::fabs(mean - 0.5) < 0.02, "the field's mean is the range's middle, got " + std::to_string(mean));
    }
  }
  // Length 0: the paper's draw, uniform in the range from the voxel's own hash.
  opal::ModelParameters paper;
  const opal::DiameterField independent(paper);
  const opal::Grid grid = opal::Grid::fromParameters(paper);
  long long differing = 0;
  for (int i = 0; i < 5000; ++i)
  {
    const int x = (i * 37) % 160, y = (i * 11) % 80, z = (i * 7) % 200;
    const std::int64_t index = grid.linearIndex(x, y, z);
    const double u = opal::unitFromHash(
      opal::hashCounter(paper.Seed, opal::RandomStream::ScatteringDiameter, static_cast<std::uint64_t>(index)));
    const double range = paper.ScatteringDiameterRange[1] - paper.ScatteringDiameterRange[0];
    differing += independent.at(x, y, z) != paper.ScatteringDiameterRange[0] + range * u ? 1 : 0;
  }
  OPAL_CHECK(differing == 0, "length 0 is the paper's independent draw, bit for bit");
  return opaltest::finish("TestOpalDiameterField");
}
