// The live view's frame budget and refinement passes (docs/design.md §5.2),
// as plain arithmetic: previews of a known cost line (fixed + per pixel) lead
// the budget to the finest scale that keeps it, whatever the first guess; no
// budget keeps the fixed scale; the passes after a coarse preview run coarse
// to fine and end with the final frame itself.
#include "OpalFrameBudget.h"
#include "OpalRefinementPasses.h"
#include "OpalTestHarness.h"

#include <string>

namespace
{
// A machine whose previews cost 5 ms plus 2 us a pixel.
double costOf(double pixels)
{
  return 0.005 + 2e-6 * pixels;
}

// The scale the budget settles on after a drag of 12 frames at 800 x 600.
int settledScale(double budget)
{
  opal::FrameBudget frames;
  frames.setBudget(budget, 2);
  int scale = frames.scaleFor(800, 600);
  for (int frame = 0; frame < 12; ++frame)
  {
    const double pixels = opal::previewPixels(800, 600, scale);
    frames.record(pixels, costOf(pixels));
    scale = frames.scaleFor(800, 600);
  }
  return scale;
}

// The finest scale whose cost is within the budget's headroom, found by trying every one.
int finestKept(double budget)
{
  for (int scale = 1; scale < opal::MaxBudgetScale; ++scale)
  {
    if (costOf(opal::previewPixels(800, 600, scale)) <= 0.85 * budget)
    {
      return scale;
    }
  }
  return opal::MaxBudgetScale;
}

void checkBudget()
{
  for (double budget : { 0.02, 0.05, 0.1, 0.3, 1.0 })
  {
    const int scale = settledScale(budget);
    OPAL_CHECK(scale == finestKept(budget),
      "a " + std::to_string(budget) + " s budget settles on scale " + std::to_string(finestKept(budget)) + ", got " +
        std::to_string(scale));
  }
  OPAL_CHECK(settledScale(1e-4) == opal::MaxBudgetScale, "a budget no preview keeps takes the coarsest");
  // A small preview that cost more than large ones (a light pass in it) does not make every size look cheap.
  opal::FrameBudget outlier;
  outlier.setBudget(0.1, 2);
  outlier.record(opal::previewPixels(800, 600, 4), costOf(opal::previewPixels(800, 600, 4)));
  outlier.record(opal::previewPixels(800, 600, 9), 0.8);
  OPAL_CHECK(outlier.scaleFor(800, 600) > 4, "an outlier coarsens the previews, got scale " +
      std::to_string(outlier.scaleFor(800, 600)));
  opal::FrameBudget none;
  none.setBudget(0, 3);
  none.record(1000, 10);
  OPAL_CHECK(none.scaleFor(800, 600) == 3, "no budget keeps the fixed scale");
  opal::FrameBudget fresh;
  fresh.setBudget(0.1, 2);
  OPAL_CHECK(fresh.scaleFor(800, 600) == 2, "before any preview is measured, the fixed scale");
  OPAL_CHECK(opal::previewPixels(801, 600, 2) == 401 * 300, "a preview's size is rounded up");
}

void checkPasses()
{
  opal::RenderParameters preview;
  preview.Quality = opal::RenderQuality::Preview;
  preview.PreviewScale = 8;
  opal::RenderParameters finalFrame = preview;
  finalFrame.Quality = opal::RenderQuality::Final;
  finalFrame.LightPosition = { 10, 50, 0 };
  const std::vector<opal::RenderParameters> passes = opal::refinementPasses(preview, finalFrame);
  OPAL_CHECK(passes.size() == 3 && passes[0].PreviewScale == 4 && passes[1].PreviewScale == 2,
    "after a preview at 1/8: a quarter, a half, then the final frame");
  OPAL_CHECK(passes[0].LightPosition == preview.LightPosition && passes[1].Quality == opal::RenderQuality::Preview,
    "the previews keep the preview's light");
  OPAL_CHECK(passes.back().LightPosition == finalFrame.LightPosition &&
      passes.back().Quality == opal::RenderQuality::Final,
    "the last pass is the final frame");
  preview.PreviewScale = 2;
  OPAL_CHECK(opal::refinementPasses(preview, finalFrame).size() == 1, "after a preview at 1/2: the final frame only");
}
} // namespace

int TestOpalFrameBudget(int, char*[])
{
  checkBudget();
  checkPasses();
  return opaltest::finish("TestOpalFrameBudget");
}
