// The one place a frame's effective settings are decided (docs/design.md §3.2):
// the render parameters as asked, completed by what the volume records of its
// preset (field data written by the source), then the quality's reductions.
// The VTK filter's RequestInformation and RequestData, its background frames
// and the render session all take the frame from here, so a preview through
// any of them is the same preview. Plain data.
#pragma once

#include "OpalRenderParameters.h"

#include <array>
#include <string>

namespace opal
{

// What a volume records for its render (the source's field data): the
// preset's image size, placement and refractive index. Defaults: the render
// parameters' own.
struct VolumeRenderHints
{
  std::array<int, 2> ImageSize = RenderParameters().ImageSize;
  std::array<double, 3> PresetRotation = RenderParameters().PresetRotation;
  double RefractiveIndex = RenderParameters().RefractiveIndex;
};

struct ResolvedFrame
{
  // What the frame renders with: the hints filled in, the quality's
  // reductions applied (withQuality), Quality Final.
  RenderParameters Parameters;
  // The preview's own stages (docs/design.md §3.4): the light field read per
  // voxel and the march step PreviewStepScale x the final's.
  bool Preview = false;
  // Empty if the parameters as asked (hints filled in) are valid, else
  // validate's sentence naming the parameter: checked before the reductions,
  // which would hide a bad SpectralNodes or WavelengthStep.
  std::string Error;
};

// ImageSize 0 x 0 takes the volume's, RefractiveIndex 0 the volume's, and
// with presetPlacement the preset's rotation replaces PresetRotation.
ResolvedFrame resolveFrame(RenderParameters asked, const VolumeRenderHints& hints, bool presetPlacement);

// A frame with nothing to fill in from a volume (the parameters complete).
ResolvedFrame resolveFrame(const RenderParameters& asked);

} // namespace opal
