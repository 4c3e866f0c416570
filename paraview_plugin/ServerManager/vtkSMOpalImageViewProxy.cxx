#include "vtkSMOpalImageViewProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSMPropertyHelper.h"

vtkStandardNewMacro(vtkSMOpalImageViewProxy);

vtkSMOpalImageViewProxy::vtkSMOpalImageViewProxy() = default;
vtkSMOpalImageViewProxy::~vtkSMOpalImageViewProxy() = default;

void vtkSMOpalImageViewProxy::CreateVTKObjects()
{
  const bool existed = this->ObjectsCreated != 0;
  this->Superclass::CreateVTKObjects();
  if (existed || !this->ObjectsCreated)
  {
    return;
  }
  // An image is looked at straight on: pan and zoom, no rotation.
  constexpr int InteractionMode2D = 1; // vtkPVRenderView::INTERACTION_MODE_2D
  vtkSMPropertyHelper(this, "InteractionMode").Set(InteractionMode2D);
  vtkSMPropertyHelper(this, "CameraParallelProjection").Set(1);
  vtkSMPropertyHelper(this, "OrientationAxesVisibility").Set(0);
  this->UpdateVTKObjects();
}

void vtkSMOpalImageViewProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
