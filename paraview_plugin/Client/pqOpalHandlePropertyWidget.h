/**
 * @class pqOpalHandlePropertyWidget
 * @brief The panel's widget for a light or eye position: three numbers and a
 * labelled, coloured 3-D handle (docs/design.md §5.3).
 *
 * The property group's panel_widget "OpalHandle". Its `<Hints><OpalHandle
 * label="Light" color="1 0.8 0.2" offset="10 8" priority="0.6"/></Hints>` give
 * the handle's label, colour, label offset and, optionally, its priority for
 * the mouse (the Light's above the Eye's 0.5, VTK's default: where they
 * coincide a drag moves the light). The handle is drawn in 3-D render views
 * only: an Opal Image View shows the render's 2-D image, where a point of the
 * stone's scene has no place.
 */
#pragma once

#include "pqInteractivePropertyWidget.h"

class pqOpalHandlePropertyWidget : public pqInteractivePropertyWidget
{
  Q_OBJECT
  typedef pqInteractivePropertyWidget Superclass;

public:
  pqOpalHandlePropertyWidget(vtkSMProxy* smproxy, vtkSMPropertyGroup* smgroup, QWidget* parent = nullptr);
  ~pqOpalHandlePropertyWidget() override;

  void setView(pqView* view) override;

protected Q_SLOTS:
  void placeWidget() override;

private:
  Q_DISABLE_COPY(pqOpalHandlePropertyWidget)

  void addPositionEditors(vtkSMPropertyGroup* smgroup);
  void styleHandle(vtkSMPropertyGroup* smgroup);
};
