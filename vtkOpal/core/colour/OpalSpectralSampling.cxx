#include "OpalSpectralSampling.h"

#include "OpalEmbeddedTables.h"
#include "OpalOptics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

namespace opal
{

namespace
{
struct Table
{
  std::vector<double> Lambda;
  std::vector<std::vector<double>> Columns;

  // Parses "lambda,v1,v2,..." lines, skipping '#' comments.
  static Table parse(const char* csv)
  {
    Table table;
    std::istringstream lines(csv);
    std::string line;
    while (std::getline(lines, line))
    {
      if (line.empty() || line[0] == '#')
      {
        continue;
      }
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream fields(line);
      double value;
      fields >> value;
      table.Lambda.push_back(value);
      std::size_t column = 0;
      while (fields >> value)
      {
        if (table.Columns.size() <= column)
        {
          table.Columns.emplace_back();
        }
        table.Columns[column++].push_back(value);
      }
    }
    return table;
  }

  // Linear interpolation; outside the table, `clampEnds` holds the end values, else 0.
  double at(std::size_t column, double lambda, bool clampEnds) const
  {
    const std::vector<double>& values = this->Columns[column];
    if (lambda <= this->Lambda.front())
    {
      return clampEnds || lambda == this->Lambda.front() ? values.front() : 0.0;
    }
    if (lambda >= this->Lambda.back())
    {
      return clampEnds || lambda == this->Lambda.back() ? values.back() : 0.0;
    }
    const auto upper = std::upper_bound(this->Lambda.begin(), this->Lambda.end(), lambda);
    const std::size_t i = static_cast<std::size_t>(upper - this->Lambda.begin());
    const double f = (lambda - this->Lambda[i - 1]) / (this->Lambda[i] - this->Lambda[i - 1]);
    return values[i - 1] + f * (values[i] - values[i - 1]);
  }
};

const Table& colourMatchingTable()
{
  static const Table table = Table::parse(embedded::cie1931Xyz2DegreeCsv());
  return table;
}

const Table& d65Table()
{
  static const Table table = Table::parse(embedded::cieD65Csv());
  return table;
}

// Mean of f over [a, b] by the midpoint rule at 0.1 nm, fine against 1 nm tables.
template <typename F>
double binAverage(F&& f, double a, double b)
{
  const int n = std::max(1, static_cast<int>(std::ceil((b - a) / 0.1)));
  double sum = 0;
  for (int i = 0; i < n; ++i)
  {
    sum += f(a + (i + 0.5) * (b - a) / n);
  }
  return sum / n;
}
} // namespace

double cieColourMatching(int component, double lambda)
{
  return colourMatchingTable().at(static_cast<std::size_t>(component), lambda, false);
}

double cieD65(double lambda)
{
  return d65Table().at(0, lambda, true);
}

int wavelengthBinCount(double lo, double hi, double step)
{
  return static_cast<int>(std::floor((hi - lo) / step + 1e-3)) + 1;
}

std::vector<WavelengthBin> sampleWavelengths(double lo, double hi, double step)
{
  std::vector<WavelengthBin> bins;
  const int count = wavelengthBinCount(lo, hi, step);
  for (int i = 0; i < count; ++i)
  {
    const double lambda = lo + i * step;
    const double a = lambda - 0.5 * step;
    const double b = lambda + 0.5 * step;
    WavelengthBin bin;
    bin.Lambda = lambda;
    bin.Width = step;
    bin.RayleighScale = std::pow(ReferenceWavelengthNm / lambda, 4.0);
    bin.D65 = binAverage([](double l) { return cieD65(l); }, a, b);
    bin.XBar = binAverage([](double l) { return cieColourMatching(0, l); }, a, b);
    bin.YBar = binAverage([](double l) { return cieColourMatching(1, l); }, a, b);
    bin.ZBar = binAverage([](double l) { return cieColourMatching(2, l); }, a, b);
    bins.push_back(bin);
  }
  double luminance = 0;
  for (const WavelengthBin& bin : bins)
  {
    luminance += bin.D65 * bin.YBar * bin.Width;
  }
  for (WavelengthBin& bin : bins)
  {
    bin.D65Scale = luminance > 0 ? 1.0 / luminance : 0.0;
    bin.D65 *= bin.D65Scale;
  }
  return bins;
}

} // namespace opal
