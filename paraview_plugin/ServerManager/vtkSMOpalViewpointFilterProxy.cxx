#include "vtkSMOpalViewpointFilterProxy.h"

#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "vtkSMOpalPipelineWalk.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkObjectFactory.h"
#include "vtkPVDataInformation.h"
#include "vtkSMEnumerationDomain.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMPropertyLink.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkNew.h"

#include <cstring>
#include <string>

vtkStandardNewMacro(vtkSMOpalViewpointFilterProxy);

namespace
{
// What the render and the Bragg map share: one light, one eye, one turn of
// the stone, one refractive index (docs/design.md §4).
constexpr const char* SharedProperties[] = { "LightPosition", "EyePosition", "ModelRotation", "RefractiveIndex" };

bool hasSharedProperties(vtkSMProxy* proxy)
{
  for (const char* name : SharedProperties)
  {
    if (!proxy->GetProperty(name))
    {
      return false;
    }
  }
  return true;
}

// The volume rendering of a Bragg map draws the domains only: BraggWavelength's
// opacity 0 below the visible 380 nm (outside domains it is 0), 1 from there.
// The Visible spectrum map never rescales, so neither does this; a function
// the user has edited is kept.
void hideOutsideDomains(vtkSMSessionProxyManager* proxyManager)
{
  vtkNew<vtkSMTransferFunctionManager> functions;
  vtkSMProxy* opacity = functions->GetOpacityTransferFunction("BraggWavelength", proxyManager);
  vtkSMProperty* points = opacity ? opacity->GetProperty("Points") : nullptr;
  if (!points || !points->IsValueDefault())
  {
    return;
  }
  const double edges[] = { 0.0, 0.0, 0.5, 0.0, 379.9, 0.0, 0.5, 0.0, 380.0, 1.0, 0.5, 0.0, 780.0, 1.0, 0.5, 0.0 };
  vtkSMPropertyHelper(points).Set(edges, 16);
  opacity->UpdateVTKObjects();
}

// A domain is one voxel thick: sampled between voxels, its wavelength blends
// with the 0 around it into the blues of short wavelengths it does not
// diffract. The nearest voxel keeps each domain's own colour.
void sampleNearest(vtkSMProxy* representation)
{
  vtkSMProperty* interpolation = representation->GetProperty("InterpolationType");
  auto* entries = interpolation ? interpolation->FindDomain<vtkSMEnumerationDomain>() : nullptr;
  if (entries && entries->HasEntryText("Nearest"))
  {
    vtkSMPropertyHelper(interpolation).Set(entries->GetEntryValueForText("Nearest"));
  }
}
} // namespace

vtkSMOpalViewpointFilterProxy::vtkSMOpalViewpointFilterProxy() = default;
vtkSMOpalViewpointFilterProxy::~vtkSMOpalViewpointFilterProxy()
{
  this->UnfollowRender();
}

void vtkSMOpalViewpointFilterProxy::SetPropertyModifiedFlag(const char* name, int flag)
{
  this->Superclass::SetPropertyModifiedFlag(name, flag);
  if (!flag || !name || std::strcmp(name, "Input") != 0 || !hasSharedProperties(this))
  {
    return;
  }
  if (vtkSMProxy* volume = vtkSMOpalPipelineWalk::UpstreamOpalVolume(this))
  {
    this->FillFromVolumePreset();
    this->ShareViewpoint(volume);
  }
}

void vtkSMOpalViewpointFilterProxy::AddConsumer(vtkSMProperty* property, vtkSMProxy* proxy)
{
  this->Superclass::AddConsumer(property, proxy);
  const char* group = proxy ? proxy->GetXMLGroup() : nullptr;
  if (!group || std::strcmp(group, "representations") != 0 || this->GetSessionProxyManager()->GetInLoadXMLState())
  {
    return;
  }
  if (this->IsRender() && proxy->GetProperty("MapScalars"))
  {
    vtkSMPropertyHelper(proxy, "MapScalars").Set(0);
  }
  // A Bragg map is coloured by BraggWavelength, its active scalars. Chosen
  // here, before ParaView initialises the representation: it blanks the
  // colouring of an outline (a volume's first representation), and its Volume
  // type (the Representation hint) then takes the first array by name
  // (BraggColor).
  if (!this->IsRender() && proxy->GetProperty("ColorArrayName"))
  {
    const bool volume = this->GetDataInformation(0)->DataSetTypeIsA("vtkImageData");
    vtkSMPropertyHelper(proxy, "ColorArrayName")
      .SetInputArrayToProcess(volume ? vtkDataObject::POINT : vtkDataObject::CELL, "BraggWavelength");
    if (volume)
    {
      hideOutsideDomains(this->GetSessionProxyManager());
      sampleNearest(proxy);
    }
  }
}

void vtkSMOpalViewpointFilterProxy::FillFromVolumePreset()
{
  vtkSMProxy* volume = vtkSMOpalPipelineWalk::UpstreamOpalVolume(this);
  const int preset = volume ? vtkSMPropertyHelper(volume, "Preset").GetAsInt() : opal::CustomPreset;
  const opal::VolumeRenderHints hints = opal::renderHints(preset, 0.0); // what the preset implies
  if (!opal::presetByIndex(preset))
  {
    return; // custom: the values shown stay (ImageSize 0 0: the volume's default)
  }
  vtkSMPropertyHelper(this, "ModelRotation").Set(hints.PresetRotation.data(), 3);
  if (this->GetProperty("ImageSize") && this->GetProperty("PresetPlacement"))
  {
    vtkSMPropertyHelper(this, "ImageSize").Set(hints.ImageSize.data(), 2);
    vtkSMPropertyHelper(this, "PresetPlacement").Set(0); // ModelRotation and the Bragg model now hold the preset's
  }
  // The kinds of opal's Bragg model and planes (docs/design.md §2.11).
  if (this->GetProperty("BraggModel") && this->GetProperty("LatticePlanes"))
  {
    vtkSMPropertyHelper(this, "BraggModel").Set(static_cast<int>(*hints.BraggModel));
    vtkSMPropertyHelper(this, "LatticePlanes").Set(static_cast<int>(*hints.LatticePlanes));
  }
}

void vtkSMOpalViewpointFilterProxy::ShareViewpoint(vtkSMProxy* volume)
{
  for (vtkSMProxy* other : vtkSMOpalPipelineWalk::DownstreamProxies(volume))
  {
    auto* filter = vtkSMOpalViewpointFilterProxy::SafeDownCast(other);
    if (!filter || filter == this || !hasSharedProperties(filter) || filter->IsRender() == this->IsRender())
    {
      continue;
    }
    if (!this->IsRender())
    {
      this->FollowRender(filter); // a new Bragg map follows the stone's first render
      return;
    }
    if (!filter->FollowedRender)
    {
      filter->FollowRender(this); // a new render leads the Bragg maps no render leads yet
    }
  }
}

bool vtkSMOpalViewpointFilterProxy::IsRender()
{
  return this->GetProperty("ImageSize") != nullptr;
}

void vtkSMOpalViewpointFilterProxy::FollowRender(vtkSMProxy* render)
{
  for (const char* name : SharedProperties)
  {
    this->GetProperty(name)->Copy(render->GetProperty(name));
    vtkNew<vtkSMPropertyLink> link;
    link->AddLinkedProperty(render, name, vtkSMLink::INPUT);
    link->AddLinkedProperty(this, name, vtkSMLink::OUTPUT);
    link->AddLinkedProperty(this, name, vtkSMLink::INPUT);
    link->AddLinkedProperty(render, name, vtkSMLink::OUTPUT);
    this->LinkNames.push_back(std::string("OpalViewpoint.") + std::to_string(render->GetGlobalID()) + "." +
      std::to_string(this->GetGlobalID()) + "." + name);
    this->GetSessionProxyManager()->RegisterLink(this->LinkNames.back().c_str(), link);
  }
  this->FollowedRender = render;
  // A link to a deleted proxy would crash the next change: unlink first.
  this->RenderObserver =
    render->AddObserver(vtkCommand::DeleteEvent, this, &vtkSMOpalViewpointFilterProxy::UnfollowRender);
  this->UpdateVTKObjects();
}

void vtkSMOpalViewpointFilterProxy::UnfollowRender()
{
  vtkSMSessionProxyManager* manager = this->GetSession() ? this->GetSessionProxyManager() : nullptr;
  for (const std::string& name : this->LinkNames)
  {
    if (manager)
    {
      manager->UnRegisterLink(name.c_str());
    }
  }
  this->LinkNames.clear();
  if (this->FollowedRender)
  {
    this->FollowedRender->RemoveObserver(this->RenderObserver);
  }
  this->FollowedRender = nullptr;
}

void vtkSMOpalViewpointFilterProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
