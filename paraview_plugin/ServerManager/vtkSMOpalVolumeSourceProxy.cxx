#include "vtkSMOpalVolumeSourceProxy.h"

#include "OpalModelFields.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "vtkSMOpalPipelineWalk.h"
#include "vtkSMOpalViewpointFilterProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMPropertyHelper.h"

#include <vector>

#include <cstring>

vtkStandardNewMacro(vtkSMOpalVolumeSourceProxy);

vtkSMOpalVolumeSourceProxy::vtkSMOpalVolumeSourceProxy() = default;
vtkSMOpalVolumeSourceProxy::~vtkSMOpalVolumeSourceProxy() = default;

void vtkSMOpalVolumeSourceProxy::SetPropertyModifiedFlag(const char* name, int flag)
{
  this->Superclass::SetPropertyModifiedFlag(name, flag);
  if (flag && name && std::strcmp(name, "Preset") == 0 && !this->Filling)
  {
    this->FillFromPreset();
    // The renders and Bragg maps of this volume show its preset's view settings.
    for (vtkSMProxy* consumer : vtkSMOpalPipelineWalk::DownstreamProxies(this))
    {
      if (auto* filter = vtkSMOpalViewpointFilterProxy::SafeDownCast(consumer))
      {
        filter->FillFromVolumePreset();
      }
    }
    for (unsigned int i = 0; i < this->GetNumberOfConsumers(); ++i)
    {
      this->FillRepresentation(this->GetConsumerProxy(i));
    }
  }
}

void vtkSMOpalVolumeSourceProxy::AddConsumer(vtkSMProperty* property, vtkSMProxy* proxy)
{
  this->Superclass::AddConsumer(property, proxy);
  this->FillRepresentation(proxy);
}

void vtkSMOpalVolumeSourceProxy::FillRepresentation(vtkSMProxy* representation)
{
  const char* group = representation ? representation->GetXMLGroup() : nullptr;
  if (!group || std::strcmp(group, "representations") != 0 || !representation->GetProperty("BraggModel") ||
    !representation->GetProperty("LatticePlanes") || !this->GetProperty("Preset"))
  {
    return;
  }
  const opal::VolumeRenderHints hints = opal::renderHints(vtkSMPropertyHelper(this, "Preset").GetAsInt(), 0.0);
  if (!hints.BraggModel || !hints.LatticePlanes)
  {
    return; // custom: the values shown stay
  }
  vtkSMPropertyHelper(representation, "BraggModel").Set(static_cast<int>(*hints.BraggModel));
  vtkSMPropertyHelper(representation, "LatticePlanes").Set(static_cast<int>(*hints.LatticePlanes));
  representation->UpdateVTKObjects();
}

void vtkSMOpalVolumeSourceProxy::FillFromPreset()
{
  // While the proxy is being built its properties come one by one, empty.
  for (const opal::ModelField& field : opal::presetModelFields())
  {
    if (!this->GetProperty(field.Name))
    {
      return;
    }
  }
  vtkSMPropertyHelper presetProperty(this, "Preset");
  const opal::PresetSettings* preset =
    presetProperty.GetNumberOfElements() > 0 ? opal::presetByIndex(presetProperty.GetAsInt()) : nullptr;
  if (!preset)
  {
    return; // custom (or unknown: the source refuses it with a message)
  }
  this->Filling = true;
  // Every field a preset may set (its value, else the model's default), as
  // ModelParameters::applyPreset does.
  opal::ModelParameters applied;
  applied.applyPreset(presetProperty.GetAsInt());
  for (const opal::ModelField& field : opal::presetModelFields())
  {
    const std::vector<double> values = field.Get(applied);
    vtkSMPropertyHelper helper(this, field.Name);
    const auto count = static_cast<unsigned int>(values.size());
    if (vtkSMIntVectorProperty::SafeDownCast(this->GetProperty(field.Name)))
    {
      // The helper sets an int property from ints only (enumerations, counts).
      const std::vector<int> whole(values.begin(), values.end());
      helper.Set(whole.data(), count);
    }
    else
    {
      helper.Set(values.data(), count);
    }
  }
  this->Filling = false;
}

void vtkSMOpalVolumeSourceProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
