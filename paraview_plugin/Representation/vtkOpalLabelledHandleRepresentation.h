/**
 * @class vtkOpalLabelledHandleRepresentation
 * @brief A point handle with a label and a colour of its own: the render's Light and Eye.
 *
 * ParaView's point handle (vtkPointHandleRepresentation3D) drawn in
 * HandleColor with LabelText beside it, LabelOffset pixels from the handle's
 * centre on the screen (docs/design.md §5.3). The light and the eye of a
 * render often coincide (both at 0 60 0 in the paper's set-up): their colours
 * and labels on opposite sides keep them apart.
 */
#pragma once

#include "vtkNew.h"
#include "vtkOpalRepresentationModule.h" // for export macro
#include "vtkPointHandleRepresentation3D.h"

class vtkTextActor;

class VTKOPALREPRESENTATION_EXPORT vtkOpalLabelledHandleRepresentation : public vtkPointHandleRepresentation3D
{
public:
  static vtkOpalLabelledHandleRepresentation* New();
  vtkTypeMacro(vtkOpalLabelledHandleRepresentation, vtkPointHandleRepresentation3D);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The text drawn beside the handle ("" draws none).
  void SetLabelText(const char* text);
  /// The colour of the handle and its label.
  void SetHandleColor(double red, double green, double blue);
  /// Where the label's lower left corner sits, in pixels from the handle's centre.
  vtkSetVector2Macro(LabelOffset, int);
  vtkGetVector2Macro(LabelOffset, int);

  int RenderOpaqueGeometry(vtkViewport* viewport) override;
  int RenderOverlay(vtkViewport* viewport) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkOpalLabelledHandleRepresentation();
  ~vtkOpalLabelledHandleRepresentation() override;

private:
  vtkOpalLabelledHandleRepresentation(const vtkOpalLabelledHandleRepresentation&) = delete;
  void operator=(const vtkOpalLabelledHandleRepresentation&) = delete;

  bool HasLabel();

  vtkNew<vtkTextActor> Label;
  int LabelOffset[2] = { 10, 10 };
};
