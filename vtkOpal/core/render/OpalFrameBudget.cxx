#include "OpalFrameBudget.h"

#include <algorithm>
#include <cmath>

namespace opal
{

namespace
{
// The fraction of the budget a choice aims at: a preview measured just under
// the budget is not pushed over it by the noise of the next.
constexpr double Headroom = 0.85;
} // namespace

double previewPixels(int width, int height, int scale)
{
  auto shrink = [scale](int n) { return static_cast<double>((n + scale - 1) / scale); };
  return shrink(std::max(width, 1)) * shrink(std::max(height, 1));
}

void FrameBudget::setBudget(double seconds, int fixedScale)
{
  this->Seconds = std::max(seconds, 0.0);
  this->FixedScale = std::clamp(fixedScale, 1, MaxBudgetScale);
}

void FrameBudget::record(double pixels, double seconds)
{
  if (!(pixels > 0) || !std::isfinite(seconds) || seconds < 0)
  {
    return;
  }
  this->Samples.push_back({ pixels, seconds });
  if (this->Samples.size() > KeptSamples)
  {
    this->Samples.pop_front();
  }
}

// Least squares of seconds = fixed + perPixel x pixels over the kept
// previews. With one size only the fixed part cannot be told apart: all of it
// is taken per pixel, which predicts a smaller preview too cheap, and the
// next preview, measured at its own size, separates the two. A fit that
// costs less for more pixels (a light pass or a busy moment in a small
// preview) is no model of the march: then too all is taken per pixel.
double FrameBudget::predicted(double pixels) const
{
  const double n = static_cast<double>(this->Samples.size());
  if (n == 0)
  {
    return 0;
  }
  double sp = 0, st = 0, spp = 0, spt = 0;
  for (const Sample& s : this->Samples)
  {
    sp += s.Pixels;
    st += s.Seconds;
    spp += s.Pixels * s.Pixels;
    spt += s.Pixels * s.Seconds;
  }
  const double spread = n * spp - sp * sp;
  double perPixel = st / sp;
  double fixed = 0;
  const double slope = spread > 1e-9 * n * spp ? (n * spt - sp * st) / spread : 0;
  if (slope > 0)
  {
    perPixel = slope;
    fixed = std::max((st - slope * sp) / n, 0.0);
  }
  return fixed + perPixel * pixels;
}

int FrameBudget::scaleFor(int width, int height) const
{
  if (this->Seconds <= 0 || this->Samples.empty())
  {
    return this->FixedScale;
  }
  for (int scale = 1; scale < MaxBudgetScale; ++scale)
  {
    if (this->predicted(previewPixels(width, height, scale)) <= Headroom * this->Seconds)
    {
      return scale;
    }
  }
  return MaxBudgetScale;
}

} // namespace opal
