/**
 * @class vtkSMOpalImageViewProxy
 * @brief The Opal Image View: a render view that starts in 2-D for the
 * Opal Spectral Render's image.
 *
 * ParaView's RenderView cannot be given other defaults by a derived XML
 * definition (a redefined property conflicts and the base's wins), so this
 * proxy sets them once its objects exist: 2-D interaction, parallel
 * projection, no orientation axes. The render filter's View hint opens its
 * image in one (docs/design.md §6.2).
 */
#pragma once

#include "vtkOpalServerManagerModule.h" // for export macro
#include "vtkSMRenderViewProxy.h"

class VTKOPALSERVERMANAGER_EXPORT vtkSMOpalImageViewProxy : public vtkSMRenderViewProxy
{
public:
  static vtkSMOpalImageViewProxy* New();
  vtkTypeMacro(vtkSMOpalImageViewProxy, vtkSMRenderViewProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSMOpalImageViewProxy();
  ~vtkSMOpalImageViewProxy() override;

  void CreateVTKObjects() override;

private:
  vtkSMOpalImageViewProxy(const vtkSMOpalImageViewProxy&) = delete;
  void operator=(const vtkSMOpalImageViewProxy&) = delete;
};
