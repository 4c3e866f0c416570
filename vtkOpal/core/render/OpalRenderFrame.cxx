#include "OpalRenderFrame.h"

namespace opal
{

ResolvedFrame resolveFrame(RenderParameters asked, const VolumeRenderHints& hints, bool presetPlacement)
{
  if (asked.ImageSize[0] == 0 && asked.ImageSize[1] == 0)
  {
    asked.ImageSize = hints.ImageSize;
  }
  if (asked.RefractiveIndex == 0)
  {
    asked.RefractiveIndex = hints.RefractiveIndex;
  }
  if (presetPlacement)
  {
    asked.PresetRotation = hints.PresetRotation;
  }
  return resolveFrame(asked);
}

ResolvedFrame resolveFrame(const RenderParameters& asked)
{
  ResolvedFrame frame;
  frame.Parameters = withQuality(asked);
  frame.Preview = asked.Quality == RenderQuality::Preview;
  frame.Error = validate(asked);
  return frame;
}

} // namespace opal
