// The live view's previews under a frame budget (docs/design.md §5.2): the
// cost of the last previews, fitted as seconds = fixed + per pixel x pixels,
// chooses the next preview's PreviewScale, the finest whose predicted time
// stays within the budget. Plain data and arithmetic: no clock, no VTK.
#pragma once

#include <cstddef>
#include <deque>

namespace opal
{

// The coarsest preview: 1/16 of the width and of the height.
constexpr int MaxBudgetScale = 16;

class FrameBudget
{
public:
  // A budget of 0 s keeps the previews at fixedScale.
  void setBudget(double seconds, int fixedScale);
  double budget() const { return this->Seconds; }

  // A preview of this many pixels took this many seconds (render and drawing).
  void record(double pixels, double seconds);
  // The costs measured so far no longer hold (a new volume or new settings).
  void forget() { this->Samples.clear(); }

  // The PreviewScale for a view of width x height pixels.
  int scaleFor(int width, int height) const;

  // Seconds a preview of this many pixels is predicted to take (0 before any is measured).
  double predicted(double pixels) const;

private:
  struct Sample
  {
    double Pixels;
    double Seconds;
  };
  // The last previews' costs: enough to fit the line, few enough to follow
  // the view as the stone fills more or less of it.
  static constexpr std::size_t KeptSamples = 8;
  std::deque<Sample> Samples;
  double Seconds = 0.1;
  int FixedScale = 2;
};

// Pixels of a preview of a width x height view at this PreviewScale.
double previewPixels(int width, int height, int scale);

} // namespace opal
