#include "OpalRenderFrame.h"

#include "OpalPresets.h"

namespace opal
{

VolumeRenderHints renderHints(int presetIndex, double refractiveIndex)
{
  VolumeRenderHints hints;
  hints.RefractiveIndex = refractiveIndex;
  if (const PresetSettings* preset = presetByIndex(presetIndex))
  {
    hints.ImageSize = preset->ImageSize;
    hints.PresetRotation = { preset->RotateXDegrees, 0.0, 0.0 };
    hints.BraggModel = preset->BraggModel;
    hints.LatticePlanes = preset->LatticePlanes;
    hints.ScatteringOrders = preset->ScatteringOrders;
  }
  return hints;
}

std::array<double, RenderHintsSize> packHints(const VolumeRenderHints& h)
{
  // -1: no Bragg model or planes of the volume's own.
  return { double(h.ImageSize[0]), double(h.ImageSize[1]), h.PresetRotation[0], h.PresetRotation[1],
    h.PresetRotation[2], h.RefractiveIndex, h.BraggModel ? double(*h.BraggModel) : -1.0,
    h.LatticePlanes ? double(*h.LatticePlanes) : -1.0, double(h.ScatteringOrders) };
}

VolumeRenderHints unpackHints(const double* v)
{
  VolumeRenderHints h;
  h.ImageSize = { static_cast<int>(v[0]), static_cast<int>(v[1]) };
  h.PresetRotation = { v[2], v[3], v[4] };
  h.RefractiveIndex = v[5];
  if (v[6] >= 0)
  {
    h.BraggModel = static_cast<BraggModelKind>(static_cast<int>(v[6]));
  }
  if (v[7] >= 0)
  {
    h.LatticePlanes = static_cast<LatticePlaneSet>(static_cast<int>(v[7]));
  }
  h.ScatteringOrders = static_cast<ScatteringOrdersKind>(static_cast<int>(v[8]));
  return h;
}

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
  if (asked.ScatteringOrders == ScatteringOrdersKind::Volume)
  {
    asked.ScatteringOrders = hints.ScatteringOrders;
  }
  if (presetPlacement)
  {
    asked.PresetRotation = hints.PresetRotation;
    // The default pair (the paper's) stands for the volume's; any other is used as set.
    const RenderParameters defaults;
    if (asked.BraggModel == defaults.BraggModel && asked.LatticePlanes == defaults.LatticePlanes)
    {
      asked.BraggModel = hints.BraggModel.value_or(asked.BraggModel);
      asked.LatticePlanes = hints.LatticePlanes.value_or(asked.LatticePlanes);
    }
  }
  return resolveFrame(asked);
}

ResolvedFrame resolveFrame(const RenderParameters& asked)
{
  ResolvedFrame frame;
  frame.Parameters = withQuality(asked);
  if (frame.Parameters.ScatteringOrders == ScatteringOrdersKind::Volume)
  {
    frame.Parameters.ScatteringOrders = VolumeRenderHints().ScatteringOrders;
  }
  frame.Preview = asked.Quality == RenderQuality::Preview;
  frame.Error = validate(asked);
  return frame;
}

} // namespace opal
