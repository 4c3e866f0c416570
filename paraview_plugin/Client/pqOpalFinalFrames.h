/**
 * @class pqOpalFinalFrames
 * @brief The GUI's part of the live view's final frames (docs/design.md §5.2).
 *
 * Started with the GUI (an auto-start interface of the plugin): it lets the
 * "Opal Spectral" representations of this process render their still final
 * frames on a worker thread instead of waiting for them, and, twenty times a
 * second, renders again each view of the built-in session whose stone has a
 * refinement pass ready, so each pass replaces the last without any input;
 * the pass under way is shown in the status bar. A remote server renders its
 * still frames synchronously.
 */
#pragma once

#include <QObject>
#include <QTimer>

#include <set>

class pqOpalFinalFrames : public QObject
{
  Q_OBJECT

public:
  pqOpalFinalFrames() = default;
  ~pqOpalFinalFrames() override = default;

  void startup();
  void shutdown();

private:
  // Renders each view with a ready final frame, once per frame.
  void renderViewsWithReadyFrames();

  // The refinement passes under way, in the status bar (cleared once none runs).
  void ShowProgress();

  QTimer Poll;
  bool ShowingProgress = false;
  std::set<unsigned long long> Requested; // ready frames a render was asked for
};
