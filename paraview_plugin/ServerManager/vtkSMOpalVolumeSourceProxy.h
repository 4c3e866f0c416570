/**
 * @class vtkSMOpalVolumeSourceProxy
 * @brief The Opal Volume's proxy: choosing a preset fills in the values it sets.
 *
 * When the Preset property changes, this proxy sets the properties the preset
 * stands for (its values by property name, OpalPresets.h) to the preset's values, so the panel shows what will be used and a value
 * edited afterwards is used (docs/design.md §2.8) — the rule of the command
 * line and of vtkOpalSource::SetPreset. Custom sets nothing.
 */
#pragma once

#include "vtkOpalServerManagerModule.h" // for export macro
#include "vtkSMSourceProxy.h"

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

private:
  vtkSMOpalVolumeSourceProxy(const vtkSMOpalVolumeSourceProxy&) = delete;
  void operator=(const vtkSMOpalVolumeSourceProxy&) = delete;

  // Sets the preset's values on the properties it stands for.
  void FillFromPreset();
  bool Filling = false;
};
