#include "pqOpalFinalFrames.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqRepresentation.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkCompositeRepresentation.h"
#include "vtkOpalSpectralRepresentation.h"
#include "vtkSMProxy.h"

#include <QMainWindow>
#include <QStatusBar>

namespace
{
// The Opal Spectral representation a view's representation shows (the
// active one of image data's representations, or itself), or null.
vtkOpalSpectralRepresentation* opalOf(pqRepresentation* representation)
{
  vtkObjectBase* object = representation->getProxy()->GetClientSideObject();
  if (auto* composite = vtkCompositeRepresentation::SafeDownCast(object))
  {
    object = composite->GetActiveRepresentation();
  }
  return vtkOpalSpectralRepresentation::SafeDownCast(object);
}
} // namespace

void pqOpalFinalFrames::startup()
{
  vtkOpalSpectralRepresentation::SetFinalFramesInBackground(true);
  // Polled, not signalled: the worker thread touches no Qt or VTK object.
  QObject::connect(&this->Poll, &QTimer::timeout, this, &pqOpalFinalFrames::renderViewsWithReadyFrames);
  this->Poll.start(50);
}

void pqOpalFinalFrames::shutdown()
{
  this->Poll.stop();
  vtkOpalSpectralRepresentation::SetFinalFramesInBackground(false);
}

void pqOpalFinalFrames::renderViewsWithReadyFrames()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  std::set<unsigned long long> ready;
  for (pqView* view : model->findItems<pqView*>())
  {
    // A remote server's representations render there, synchronously.
    if (view->getServer()->isRemote())
    {
      continue;
    }
    bool render = false;
    for (pqRepresentation* representation : view->getRepresentations())
    {
      vtkOpalSpectralRepresentation* opal = opalOf(representation);
      const unsigned long long frame = opal ? opal->GetReadyFinalFrame() : 0;
      if (frame > 0)
      {
        // Once per frame: a render that could not draw it (the stone out of
        // sight) is not repeated ten times a second.
        render = render || this->Requested.count(frame) == 0;
        ready.insert(frame);
      }
    }
    if (render)
    {
      view->render();
    }
  }
  this->Requested = ready;
  this->ShowProgress();
}

// The passes under way, in the main window's status bar: the GUI stays free
// (ParaView's own progress bar would lock its input while it shows).
void pqOpalFinalFrames::ShowProgress()
{
  auto* window = qobject_cast<QMainWindow*>(pqCoreUtilities::mainWidget());
  if (!window)
  {
    return;
  }
  QString message;
  for (pqRepresentation* representation :
    pqApplicationCore::instance()->getServerManagerModel()->findItems<pqRepresentation*>())
  {
    vtkOpalSpectralRepresentation* opal = opalOf(representation);
    int pass = 0, passes = 0;
    double fraction = 0;
    if (opal && opal->GetRefinementProgress(pass, passes, fraction))
    {
      message = QString("Opal Spectral: pass %1 of %2, %3%").arg(pass).arg(passes).arg(int(100 * fraction));
    }
  }
  if (!message.isEmpty() || this->ShowingProgress)
  {
    window->statusBar()->showMessage(message);
  }
  this->ShowingProgress = !message.isEmpty();
}
