// The one place a frame's effective settings are decided (docs/design.md §3.2):
// the render parameters as asked, completed by what the volume records of its
// preset (field data written by the source), then the quality's reductions.
// The VTK filter's RequestInformation and RequestData, its background frames
// and the render session all take the frame from here, so a preview through
// any of them is the same preview. Plain data.
#pragma once

#include "OpalRenderParameters.h"

#include <array>
#include <optional>
#include <string>

namespace opal
{

// What a volume implies for its render: its preset's image size, placement,
// Bragg model and planes (the kinds of opal, docs/design.md §2.11) and the
// model's refractive index. Defaults: the render parameters' own; the Bragg
// model and planes unset for a custom volume (the render's as set).
struct VolumeRenderHints
{
  std::array<int, 2> ImageSize = RenderParameters().ImageSize;
  std::array<double, 3> PresetRotation = RenderParameters().PresetRotation;
  double RefractiveIndex = RenderParameters().RefractiveIndex;
  std::optional<BraggModelKind> BraggModel;
  std::optional<LatticePlaneSet> LatticePlanes;
  ScatteringOrdersKind ScatteringOrders = ScatteringOrdersKind::All;
};

// The one owner of what a volume of this preset (1-based; CustomPreset or an
// unknown index: none) and refractive index implies for its render
// (docs/design.md §2.8): the source's pipeline information, a saved volume's
// field data, opal-render and ParaView's proxies all take it from here.
VolumeRenderHints renderHints(int presetIndex, double refractiveIndex);

// The hints as the numbers of one pipeline information key (the VTK source's
// RENDER_HINTS), and back; the packed form has RenderHintsSize values.
constexpr int RenderHintsSize = 9;
std::array<double, RenderHintsSize> packHints(const VolumeRenderHints& hints);
VolumeRenderHints unpackHints(const double* values);

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

// ImageSize 0 x 0 takes the volume's, RefractiveIndex 0 and ScatteringOrders
// Volume the volume's, and
// with presetPlacement the preset's rotation replaces PresetRotation and, if
// the Bragg model and planes asked are the defaults (the paper's), the
// preset's replace them (a kind of opal's; any other pair is used as set).
ResolvedFrame resolveFrame(RenderParameters asked, const VolumeRenderHints& hints, bool presetPlacement);

// A frame with nothing to fill in from a volume (the parameters complete;
// ScatteringOrders Volume: a custom volume's, all).
ResolvedFrame resolveFrame(const RenderParameters& asked);

} // namespace opal
