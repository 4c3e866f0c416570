#include "vtkOpalLabelledHandleRepresentation.h"

#include "vtkObjectFactory.h"
#include "vtkProperty.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkViewport.h"

vtkStandardNewMacro(vtkOpalLabelledHandleRepresentation);

vtkOpalLabelledHandleRepresentation::vtkOpalLabelledHandleRepresentation()
{
  vtkTextProperty* text = this->Label->GetTextProperty();
  text->SetFontSize(16);
  text->SetBold(true);
  text->SetShadow(true);
  this->Label->SetInput("");
  this->SetHandleColor(1.0, 1.0, 1.0); // the stock handle's white until the hint colours it
}

vtkOpalLabelledHandleRepresentation::~vtkOpalLabelledHandleRepresentation() = default;

void vtkOpalLabelledHandleRepresentation::SetLabelText(const char* text)
{
  this->Label->SetInput(text ? text : "");
  this->Modified();
}

void vtkOpalLabelledHandleRepresentation::SetHandleColor(double red, double green, double blue)
{
  this->GetProperty()->SetColor(red, green, blue);
  this->Label->GetTextProperty()->SetColor(red, green, blue);
  this->Modified();
}

bool vtkOpalLabelledHandleRepresentation::HasLabel()
{
  const char* text = this->Label->GetInput();
  return text && *text;
}

// The label follows the handle on the screen: its display position is taken
// at every opaque pass, where the text actor also lays out its texture; it
// is drawn over the scene in the overlay pass.
int vtkOpalLabelledHandleRepresentation::RenderOpaqueGeometry(vtkViewport* viewport)
{
  int rendered = this->Superclass::RenderOpaqueGeometry(viewport);
  if (this->HasLabel())
  {
    double position[3];
    this->GetWorldPosition(position);
    viewport->SetWorldPoint(position[0], position[1], position[2], 1.0);
    viewport->WorldToDisplay();
    const double* display = viewport->GetDisplayPoint();
    this->Label->SetDisplayPosition(
      static_cast<int>(display[0]) + this->LabelOffset[0], static_cast<int>(display[1]) + this->LabelOffset[1]);
    rendered += this->Label->RenderOpaqueGeometry(viewport);
  }
  return rendered;
}

int vtkOpalLabelledHandleRepresentation::RenderOverlay(vtkViewport* viewport)
{
  return this->Superclass::RenderOverlay(viewport) + (this->HasLabel() ? this->Label->RenderOverlay(viewport) : 0);
}

void vtkOpalLabelledHandleRepresentation::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Superclass::ReleaseGraphicsResources(window);
  this->Label->ReleaseGraphicsResources(window);
}

void vtkOpalLabelledHandleRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  // The proxy's properties by name (TestOpalXmlDefaults reads them here).
  const char* text = this->Label->GetInput();
  os << indent << "LabelText: " << (text ? text : "") << "\n";
  os << indent << "LabelOffset: " << this->LabelOffset[0] << " " << this->LabelOffset[1] << "\n";
  const double* color = this->Label->GetTextProperty()->GetColor();
  os << indent << "HandleColor: " << color[0] << " " << color[1] << " " << color[2] << "\n";
  double position[3];
  this->GetWorldPosition(position);
  os << indent << "WorldPosition: " << position[0] << " " << position[1] << " " << position[2] << "\n";
}
