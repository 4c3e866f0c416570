#include "pqOpalHandlePropertyWidget.h"

#include "pqDoubleLineEdit.h"
#include "pqView.h"
#include "vtkAbstractWidget.h"
#include "vtkPVXMLElement.h"
#include "vtkSMPropertyGroup.h"
#include "vtkSMNewWidgetRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QCheckBox>
#include <QGridLayout>

#include <cstring>

pqOpalHandlePropertyWidget::pqOpalHandlePropertyWidget(
  vtkSMProxy* smproxy, vtkSMPropertyGroup* smgroup, QWidget* parent)
  : Superclass("representations", "OpalHandleWidgetRepresentation", smproxy, smgroup, parent)
{
  this->addPositionEditors(smgroup);
  this->styleHandle(smgroup);
}

pqOpalHandlePropertyWidget::~pqOpalHandlePropertyWidget() = default;

// x, y, z linked to the group's WorldPosition property (the superclass links
// the handle to it), and the check box that shows or hides the handle.
void pqOpalHandlePropertyWidget::addPositionEditors(vtkSMPropertyGroup* smgroup)
{
  auto* layout = new QGridLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  vtkSMProperty* position = smgroup->GetProperty("WorldPosition");
  for (int axis = 0; position && axis < 3; ++axis)
  {
    auto* edit = new pqDoubleLineEdit(this);
    edit->setObjectName(QString("Position%1").arg(axis));
    layout->addWidget(edit, 0, axis);
    this->addPropertyLink(edit, "text2", SIGNAL(textChangedAndEditingFinished()), position, axis);
  }
  auto* show = new QCheckBox(tr("Show %1").arg(smgroup->GetXMLLabel()), this);
  show->setObjectName("Show3DWidget");
  show->setChecked(true);
  layout->addWidget(show, 1, 0, 1, 3);
  this->connect(show, &QCheckBox::toggled, this, &pqOpalHandlePropertyWidget::setWidgetVisible);
  show->connect(this, &pqOpalHandlePropertyWidget::widgetVisibilityToggled, show, &QCheckBox::setChecked);
  this->setWidgetVisible(show->isChecked());
}

// Label, colour and label offset from the group's OpalHandle hint.
void pqOpalHandlePropertyWidget::styleHandle(vtkSMPropertyGroup* smgroup)
{
  vtkPVXMLElement* hints = smgroup->GetHints();
  vtkPVXMLElement* style = hints ? hints->FindNestedElementByName("OpalHandle") : nullptr;
  if (!style)
  {
    return;
  }
  vtkSMProxy* handle = this->widgetProxy();
  if (const char* label = style->GetAttribute("label"))
  {
    vtkSMPropertyHelper(handle, "LabelText").Set(label);
  }
  double color[3];
  if (style->GetVectorAttribute("color", 3, color) == 3)
  {
    vtkSMPropertyHelper(handle, "HandleColor").Set(color, 3);
  }
  int offset[2];
  if (style->GetVectorAttribute("offset", 2, offset) == 2)
  {
    vtkSMPropertyHelper(handle, "LabelOffset").Set(offset, 2);
  }
  handle->UpdateVTKObjects();
  // Where two handles coincide (the light and the eye in the paper's set-up)
  // the one of higher priority takes the click; among equals VTK serves the
  // last enabled first, which was the Eye.
  double priority = 0.0;
  auto* widgetProxy = vtkSMNewWidgetRepresentationProxy::SafeDownCast(handle);
  vtkAbstractWidget* widget = widgetProxy ? widgetProxy->GetWidget() : nullptr;
  if (widget && style->GetScalarAttribute("priority", &priority))
  {
    widget->SetPriority(static_cast<float>(priority));
  }
}

void pqOpalHandlePropertyWidget::setView(pqView* view)
{
  // The render's 2-D image has no place for a point of the stone's scene.
  const bool imageView =
    view && view->getProxy() && std::strcmp(view->getProxy()->GetXMLName(), "OpalImageView") == 0;
  this->Superclass::setView(imageView ? nullptr : view);
}

void pqOpalHandlePropertyWidget::placeWidget()
{
  // A position needs no placing in bounds.
}
