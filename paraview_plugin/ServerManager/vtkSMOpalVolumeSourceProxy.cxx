#include "vtkSMOpalVolumeSourceProxy.h"

#include "OpalModelParameters.h"
#include "OpalPresets.h"
#include "vtkSMOpalPipelineWalk.h"
#include "vtkSMOpalViewpointFilterProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSMPropertyHelper.h"

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
  }
}

void vtkSMOpalVolumeSourceProxy::FillFromPreset()
{
  // While the proxy is being built its properties come one by one, empty.
  for (const char* name : { "Preset", "DomainDiameterRange", "DomainLayout", "VoronoiCellCount",
         "VoronoiWeightSpread", "OrderedFraction" })
  {
    if (!this->GetProperty(name))
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
  vtkSMPropertyHelper(this, "DomainDiameterRange").Set(preset->DomainDiameterRange.data(), 2);
  if (preset->Voronoi)
  {
    vtkSMPropertyHelper(this, "DomainLayout").Set(static_cast<int>(opal::DomainLayoutKind::Voronoi));
    vtkSMPropertyHelper(this, "VoronoiCellCount").Set(preset->Voronoi->CellCount);
    vtkSMPropertyHelper(this, "VoronoiWeightSpread").Set(preset->Voronoi->WeightSpread);
    vtkSMPropertyHelper(this, "OrderedFraction").Set(preset->Voronoi->OrderedFraction);
  }
  this->Filling = false;
}

void vtkSMOpalVolumeSourceProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
