// The paper's figures as presets (docs/design.md §2.8): the parameters the paper
// varies between its figures; Voronoi opals (§2.9), which also set the
// domain layout; and the kinds of opal (§2.11), which set the body, its
// absorption and backing. Everything else keeps the model's defaults.
#pragma once

#include "OpalRenderParameters.h"

#include <array>
#include <string>
#include <vector>

namespace opal
{

// A value a preset sets, by the property's name (OpalModelFields.h).
struct PresetValue
{
  const char* Property;
  std::vector<double> Values;
};

struct PresetSettings
{
  const char* Name;
  std::array<int, 2> ImageSize;   // pixels, width x height (a render setting)
  double RotateXDegrees;          // the stone's placement: rotation about x (a render setting)
  std::vector<PresetValue> Model; // the model parameters it sets; everything else keeps its value
  // The render's Bragg model and planes (the kinds of opal: docs/design.md §2.11).
  BraggModelKind BraggModel = BraggModelKind::Paper;
  LatticePlaneSet LatticePlanes = LatticePlaneSet::Stacking111;
  // The paper's figures keep its single scattering; every other preset renders every order.
  ScatteringOrdersKind ScatteringOrders = ScatteringOrdersKind::All;

  // The values it sets for a property, or nullptr.
  const std::vector<double>* valuesOf(const char* property) const;
};

// Index 0 of the preset enumeration is "custom" (no preset); presets are 1-based.
constexpr int CustomPreset = 0;
constexpr int DefaultPreset = 3; // fig12, the paper's red opal

const std::vector<PresetSettings>& presets();

// The preset with the given 1-based index, or nullptr for CustomPreset / out of range.
const PresetSettings* presetByIndex(int index);

// 1-based index of the named preset ("fig12"), CustomPreset for "custom", -1 if unknown.
int presetIndexByName(const std::string& name);

// "custom, fig10, fig11, ..." for messages and help texts.
std::string presetNameList();

} // namespace opal
