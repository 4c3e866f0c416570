#include "vtkSMOpalVolumeSourceProxy.h"

#include "OpalModelFields.h"
#include "OpalPresets.h"
#include "OpalRenderFrame.h"
#include "OpalRenderParameters.h"
#include "vtkSMOpalPipelineWalk.h"
#include "vtkSMOpalViewpointFilterProxy.h"

#include "vtkCommand.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPVDataInformation.h"
#include "vtkSMInputProperty.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSessionProxyManager.h"

#include <algorithm>
#include <array>
#include <cmath>
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
  this->WatchFirstView(property, proxy);
}

void vtkSMOpalVolumeSourceProxy::WatchFirstView(vtkSMProperty* property, vtkSMProxy* representation)
{
  const char* group = representation ? representation->GetXMLGroup() : nullptr;
  auto* input = vtkSMInputProperty::SafeDownCast(property);
  // A state being loaded brings its own camera.
  if (!input || !group || std::strcmp(group, "representations") != 0 ||
    this->GetSessionProxyManager()->GetInLoadXMLState())
  {
    return;
  }
  bool volumePort = false;
  for (unsigned int i = 0; i < input->GetNumberOfProxies(); ++i)
  {
    volumePort = volumePort || (input->GetProxy(i) == this && input->GetOutputPortForConnection(i) == 0);
  }
  const bool watched = std::any_of(this->Watches.begin(), this->Watches.end(),
    [representation](const Watch& watch) { return watch.Representation == representation; });
  if (!volumePort || watched)
  {
    return;
  }
  Watch watch;
  watch.Representation = representation;
  watch.Observer = representation->AddObserver(
    vtkCommand::UpdateDataEvent, this, &vtkSMOpalVolumeSourceProxy::OnRepresentationUpdated);
  watch.Shown.Modified();
  this->Watches.push_back(watch);
}

void vtkSMOpalVolumeSourceProxy::OnRepresentationUpdated(vtkObject* caller, unsigned long, void*)
{
  auto found = std::find_if(this->Watches.begin(), this->Watches.end(),
    [caller](const Watch& watch) { return watch.Representation == caller; });
  if (found == this->Watches.end())
  {
    return;
  }
  const Watch watch = *found;
  this->Watches.erase(found);
  watch.Representation->RemoveObserver(watch.Observer);
  // The representation's consumers are the views it was added to.
  for (unsigned int i = 0; i < watch.Representation->GetNumberOfConsumers(); ++i)
  {
    auto* view = vtkSMRenderViewProxy::SafeDownCast(watch.Representation->GetConsumerProxy(i));
    if (view && std::strcmp(view->GetXMLName(), "RenderView") == 0)
    {
      this->LookDownOnStone(view, watch.Representation, watch.Shown.GetMTime());
    }
  }
}

void vtkSMOpalVolumeSourceProxy::LookDownOnStone(vtkSMViewProxy* view, vtkSMProxy* representation, vtkMTimeType shown)
{
  for (const char* name : { "CameraPosition", "CameraFocalPoint", "CameraViewUp" })
  {
    if (view->GetProperty(name)->GetMTime() > shown)
    {
      return; // a script or the user placed the camera
    }
  }
  vtkSMPropertyHelper shownProxies(view, "Representations");
  for (unsigned int i = 0; i < shownProxies.GetNumberOfElements(); ++i)
  {
    vtkSMProxy* other = shownProxies.GetAsProxy(i);
    if (other && other != representation && other->GetProperty("Input") &&
      vtkSMPropertyHelper(other, "Visibility", true).GetAsInt() != 0)
    {
      return; // the view's scene is someone else's
    }
  }
  // The render's own view (eye above the stone, the long axis upright), framed
  // as ParaView's camera reset frames the stone's box.
  const opal::RenderParameters paper;
  std::array<double, 3> direction{};
  vtkMath::Subtract(paper.EyePosition.data(), paper.FocalPoint.data(), direction.data());
  vtkMath::Normalize(direction.data());
  const double* bounds = this->GetDataInformation(0)->GetBounds();
  if (bounds[0] > bounds[1])
  {
    return; // nothing built yet
  }
  std::array<double, 3> centre{};
  double radius = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    centre[axis] = 0.5 * (bounds[2 * axis] + bounds[2 * axis + 1]);
    radius += 0.25 * (bounds[2 * axis + 1] - bounds[2 * axis]) * (bounds[2 * axis + 1] - bounds[2 * axis]);
  }
  const double angle = vtkMath::RadiansFromDegrees(vtkSMPropertyHelper(view, "CameraViewAngle").GetAsDouble());
  const double distance = std::sqrt(radius) / std::sin(0.5 * angle);
  std::array<double, 3> eye{};
  for (int axis = 0; axis < 3; ++axis)
  {
    eye[axis] = centre[axis] + distance * direction[axis];
  }
  vtkSMPropertyHelper(view, "CameraPosition").Set(eye.data(), 3);
  vtkSMPropertyHelper(view, "CameraFocalPoint").Set(centre.data(), 3);
  vtkSMPropertyHelper(view, "CameraViewUp").Set(paper.ViewUp.data(), 3);
  view->UpdateVTKObjects();
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
