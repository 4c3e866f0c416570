#include "OpalRefinementPasses.h"

namespace opal
{

// A final frame with one ray per pixel before the anti-aliased one was left
// out: it costs a third of the final frame (0.96 s against 2.84 s for fig12
// at 640 x 480 on two lavapipe cores) and the final frame cannot reuse it, so
// the still image would come 1.34 x later; the two previews cost about a
// twentieth of it (docs/design.md §5.2).
std::vector<RenderParameters> refinementPasses(const RenderParameters& drawnPreview, const RenderParameters& finalFrame)
{
  std::vector<RenderParameters> passes;
  for (int scale : { 4, 2 })
  {
    if (drawnPreview.Quality == RenderQuality::Preview && scale < drawnPreview.PreviewScale)
    {
      RenderParameters pass = drawnPreview;
      pass.PreviewScale = scale;
      passes.push_back(pass);
    }
  }
  passes.push_back(finalFrame);
  return passes;
}

} // namespace opal
