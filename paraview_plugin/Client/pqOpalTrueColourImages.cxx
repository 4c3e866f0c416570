#include "pqOpalTrueColourImages.h"

#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqScalarBarRepresentation.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QPointer>
#include <QTimer>

#include <cstring>

void pqOpalTrueColourImages::startup()
{
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(), &pqServerManagerModel::representationAdded,
    this, &pqOpalTrueColourImages::onRepresentationAdded);
}

void pqOpalTrueColourImages::onRepresentationAdded(pqRepresentation* representation)
{
  // A new bar is made visible after it is registered (and added to its
  // view), in the same call: it is looked at once that call is over.
  QPointer<pqScalarBarRepresentation> bar = qobject_cast<pqScalarBarRepresentation*>(representation);
  if (bar)
  {
    QTimer::singleShot(0, this, [bar]() {
      if (bar)
      {
        hideIfTrueColour(bar);
      }
    });
  }
}

void pqOpalTrueColourImages::hideIfTrueColour(pqScalarBarRepresentation* bar)
{
  pqView* view = bar->getView();
  vtkSMProxy* map = vtkSMPropertyHelper(bar->getProxy(), "LookupTable", true).GetAsProxy();
  if (!view || !map || std::strcmp(view->getProxy()->GetXMLName(), "OpalImageView") != 0 || !bar->isVisible())
  {
    return;
  }
  vtkSMProxy* trueColour = nullptr; // a shown image of this map, unmapped
  for (pqRepresentation* shown : view->getRepresentations())
  {
    auto* data = qobject_cast<pqDataRepresentation*>(shown);
    if (!data || !data->isVisible() || data->getLookupTableProxy() != map)
    {
      continue;
    }
    if (vtkSMPropertyHelper(data->getProxy(), "MapScalars", true).GetAsInt() != 0)
    {
      return; // a mapped image uses the bar
    }
    trueColour = data->getProxy();
  }
  if (trueColour)
  {
    vtkSMPVRepresentationProxy::SetScalarBarVisibility(trueColour, view->getProxy(), false);
    view->render();
  }
}
