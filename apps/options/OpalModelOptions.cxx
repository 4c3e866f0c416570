#include "OpalModelOptions.h"

#include "OpalCliTable.h"

#include "OpalModelFields.h"
#include "OpalPresets.h"

void OpalModelOptions::addTo(CLI::App& app)
{
  opal::ModelParameters& p = this->Parameters;
  std::vector<std::string> presetNames{ "custom" };
  for (const opal::PresetSettings& preset : opal::presets())
  {
    presetNames.emplace_back(preset.Name);
  }
  app.add_option("--preset", this->Preset,
       "The paper's figure to reproduce, or a Voronoi opal (harlequin, pinfire): " + opal::presetNameList())
    ->check(CLI::IsMember(presetNames))
    ->capture_default_str()
    ->group("Model");
  // Every row of the model parameters' table with a flag of its own.
  for (const opal::ParameterRow<opal::ModelParameters>& row : opal::modelParameterRows())
  {
    if (*row.Flag != '\0')
    {
      addRowOption(app, row, p, "Model");
    }
  }
  // Each flag of a value a preset may set wins over the preset when given.
  for (const opal::ModelField& field : opal::presetModelFields())
  {
    this->GivenOverPreset.emplace_back(app.get_option(field.Flag), &field);
  }
}

opal::ModelParameters OpalModelOptions::parameters() const
{
  opal::ModelParameters resolved = this->Parameters;
  resolved.applyPreset(opal::presetIndexByName(this->Preset));
  for (const auto& [option, field] : this->GivenOverPreset)
  {
    if (option->count() > 0)
    {
      field->Set(resolved, field->Get(this->Parameters));
    }
  }
  return resolved;
}

int OpalModelOptions::presetIndex() const
{
  // A flag that wins over a value the preset lists (fig15's
  // --domain-diameter-range, harlequin's layout, ...): the volume is then
  // recorded (and rebuilt by the source) as custom. A flag for a field the
  // preset only resets to the model's default (--domain-count with fig13)
  // keeps the preset's name: its placement and image size still apply.
  const int index = opal::presetIndexByName(this->Preset);
  const opal::PresetSettings* preset = opal::presetByIndex(index);
  for (const auto& [option, field] : this->GivenOverPreset)
  {
    if (preset && option->count() > 0 && preset->valuesOf(field->Name))
    {
      return opal::CustomPreset;
    }
  }
  return index;
}
