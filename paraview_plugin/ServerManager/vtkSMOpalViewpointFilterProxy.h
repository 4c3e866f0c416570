/**
 * @class vtkSMOpalViewpointFilterProxy
 * @brief The proxy of the filters that look at the stone from a light and an
 * eye (Opal Spectral Render, Opal Bragg Map): the preset's view settings in
 * the panel, and one light and eye for both.
 *
 * When its input is connected, the proxy fills in what the upstream Opal
 * Volume's preset sets for the view (the render's ImageSize; ModelRotation =
 * the preset's placement, fig13's 5 degrees about x, with the render's
 * PresetPlacement turned off so the placement is not applied twice), and
 * links a Bragg map's LightPosition, EyePosition, ModelRotation and
 * RefractiveIndex with a render of the same volume (both ways), so the map
 * shows the domains for the light and eye the render uses (docs/design.md
 * §2.8, §4). A Bragg map follows the stone's first render; a new render leads
 * the Bragg maps no render leads yet; renders stay independent of each other
 * (two eyes on one stone are a fair comparison). The render's image is shown
 * in true colours: its representations start with Map Scalars off. A Bragg
 * map's start coloured by BraggWavelength; on the volume, nearest voxels and
 * an opacity of 0 below 380 nm make its volume rendering the domains only. The
 * volume's proxy calls FillFromVolumePreset again when its preset changes.
 */
#pragma once

#include "vtkOpalServerManagerModule.h" // for export macro
#include "vtkSMSourceProxy.h"
#include "vtkWeakPointer.h" // for FollowedRender

#include <string> // for LinkNames
#include <vector> // for LinkNames

class VTKOPALSERVERMANAGER_EXPORT vtkSMOpalViewpointFilterProxy : public vtkSMSourceProxy
{
public:
  static vtkSMOpalViewpointFilterProxy* New();
  vtkTypeMacro(vtkSMOpalViewpointFilterProxy, vtkSMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sets the view settings the upstream Opal Volume's preset implies; no-op
  /// without an Opal Volume upstream (a saved volume: its field data decide at
  /// render time).
  void FillFromVolumePreset();

protected:
  vtkSMOpalViewpointFilterProxy();
  ~vtkSMOpalViewpointFilterProxy() override;

  void SetPropertyModifiedFlag(const char* name, int flag) override;
  // The render's image is colours (sRGB): its representations show them as
  // they are (Map Scalars off), not through a colour map.
  void AddConsumer(vtkSMProperty* property, vtkSMProxy* proxy) override;

private:
  vtkSMOpalViewpointFilterProxy(const vtkSMOpalViewpointFilterProxy&) = delete;
  void operator=(const vtkSMOpalViewpointFilterProxy&) = delete;

  // Pairs this filter with the volume's Bragg maps or its first render.
  void ShareViewpoint(vtkSMProxy* volume);
  // The render (not the Bragg map) has an image size.
  bool IsRender();
  // Links this Bragg map's light, eye, rotation and index with the render's,
  // taking the render's values.
  void FollowRender(vtkSMProxy* render);
  // Removes the links (the render or this map goes away).
  void UnfollowRender();
  vtkWeakPointer<vtkSMProxy> FollowedRender;
  unsigned long RenderObserver = 0;
  std::vector<std::string> LinkNames;
};
