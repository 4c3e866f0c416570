/**
 * @class vtkSMOpalVolumeSourceProxy
 * @brief The Opal Volume's proxy: choosing a preset fills in the values it sets.
 *
 * When the Preset property changes, this proxy sets the properties the preset
 * stands for (its values by property name, OpalPresets.h) to the preset's values, so the panel shows what will be used and a value
 * edited afterwards is used (docs/design.md §2.8) — the rule of the command
 * line and of vtkOpalSource::SetPreset. Custom sets nothing. Its renders and
 * Bragg maps show the preset's view settings (vtkSMOpalViewpointFilterProxy),
 * and its "Opal Spectral" representations the preset's Bragg model and planes
 * (the kinds of opal, docs/design.md §2.11), when shown and when the preset changes.
 * A render view that first shows its Volume output, holding no other data and
 * with a camera no one has set, looks down on the stone from +y as the
 * paper's figures do (the render's default eye, focal point and view up,
 * docs/design.md §5.2): from the side the play of colour is hardly seen.
 */
#pragma once

#include "vtkOpalServerManagerModule.h" // for export macro
#include "vtkSMSourceProxy.h"
#include "vtkTimeStamp.h"
#include "vtkWeakPointer.h"

#include <vector>

class vtkSMViewProxy;

class VTKOPALSERVERMANAGER_EXPORT vtkSMOpalVolumeSourceProxy : public vtkSMSourceProxy
{
public:
  static vtkSMOpalVolumeSourceProxy* New();
  vtkTypeMacro(vtkSMOpalVolumeSourceProxy, vtkSMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSMOpalVolumeSourceProxy();
  ~vtkSMOpalVolumeSourceProxy() override;

  void SetPropertyModifiedFlag(const char* name, int flag) override;
  void AddConsumer(vtkSMProperty* property, vtkSMProxy* proxy) override;

private:
  vtkSMOpalVolumeSourceProxy(const vtkSMOpalVolumeSourceProxy&) = delete;
  void operator=(const vtkSMOpalVolumeSourceProxy&) = delete;

  // Sets the preset's values on the properties it stands for.
  void FillFromPreset();
  // Sets the preset's Bragg model and planes on a representation that has them.
  void FillRepresentation(vtkSMProxy* representation);
  // Waits for the first update of a new representation of the Volume output:
  // only then is it in its view.
  void WatchFirstView(vtkSMProperty* property, vtkSMProxy* representation);
  void OnRepresentationUpdated(vtkObject* caller, unsigned long event, void* data);
  // Turns the view to look down on the stone, framing it, unless its camera
  // was set since the representation was made or other data is shown there.
  void LookDownOnStone(vtkSMViewProxy* view, vtkSMProxy* representation, vtkMTimeType shown);

  struct Watch
  {
    vtkWeakPointer<vtkSMProxy> Representation;
    unsigned long Observer;
    vtkTimeStamp Shown;
  };
  std::vector<Watch> Watches;
  bool Filling = false;
};
