#include "OpalRenderOptions.h"

#include "OpalCliTable.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"

#include <climits>

void OpalRenderOptions::addTo(CLI::App& app)
{
  opal::RenderParameters& p = this->Parameters;
  const std::string group = "Render";
  // Every row of the render parameters' table with a flag of its own.
  for (const opal::ParameterRow<opal::RenderParameters>& row : opal::renderParameterRows())
  {
    if (*row.Flag != '\0')
    {
      this->RowOptions[row.Name] = addRowOption(app, row, p, group);
    }
  }
  // Shortcuts for one component of a row, read as the row's numbers are.
  const opal::ParameterRow<opal::RenderParameters>* size = opal::findRow(opal::renderParameterRows(), "ImageSize");
  const CLI::Validator pixels = opalcli::numberCheck(size->Name, size->Min, size->Max, true);
  this->WidthOption = app.add_option("--width", p.ImageSize[0], "Image width in pixels (default: the preset's)")
                        ->transform(pixels)
                        ->group(group);
  this->HeightOption = app.add_option("--height", p.ImageSize[1], "Image height in pixels (default: the preset's)")
                         ->transform(pixels)
                         ->group(group);
  // ModelRotation's first component by another name: checked here, so a refusal names the flag given.
  app.add_option("--rotate-x", p.ModelRotation[0], "Turn the stone about x by degrees, after the preset's placement (fig13: 5)")
    ->transform(opalcli::numberCheck("ModelRotation", -opal::Unbounded, opal::Unbounded, false))
    ->group(group);
  app.add_option("--device", this->DeviceIndex, "Vulkan device index (-1: OPAL_VULKAN_DEVICE or the best)")
    ->transform(opalcli::numberCheck("DeviceIndex", -1, INT_MAX, true))
    ->capture_default_str()
    ->group(group);
  app.add_option("--device-memory-limit", this->DeviceMemoryLimit, "Refuse device memory beyond this many MB (0: none)")
    ->transform(opalcli::numberCheck("DeviceMemoryLimit", 0, INT_MAX, true))
    ->capture_default_str()
    ->group(group);
}

bool OpalRenderOptions::given(const char* name) const
{
  const auto option = this->RowOptions.find(name);
  return option != this->RowOptions.end() && option->second->count() > 0;
}

opal::RenderParameters OpalRenderOptions::parameters(const std::string& presetName, double refractiveIndex) const
{
  opal::RenderParameters p = this->Parameters;
  // What the preset implies (opal::renderHints), where no flag says otherwise.
  const opal::VolumeRenderHints hints = opal::renderHints(opal::presetIndexByName(presetName), refractiveIndex);
  const bool sizeGiven = this->given("ImageSize");
  if (!sizeGiven && this->WidthOption->count() == 0)
  {
    p.ImageSize[0] = hints.ImageSize[0];
  }
  if (!sizeGiven && this->HeightOption->count() == 0)
  {
    p.ImageSize[1] = hints.ImageSize[1];
  }
  p.PresetRotation = hints.PresetRotation;
  if (!this->given("BraggModel"))
  {
    p.BraggModel = hints.BraggModel.value_or(p.BraggModel);
  }
  if (!this->given("LatticePlanes"))
  {
    p.LatticePlanes = hints.LatticePlanes.value_or(p.LatticePlanes);
  }
  p.RefractiveIndex = hints.RefractiveIndex;
  if (!this->given("ScatteringOrders") || p.ScatteringOrders == opal::ScatteringOrdersKind::Volume)
  {
    p.ScatteringOrders = hints.ScatteringOrders;
  }
  return p;
}
