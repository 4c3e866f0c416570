/**
 * @class pqOpalTrueColourImages
 * @brief The GUI's part of the Opal Image View: no colour bar for an image in
 * its own colours (docs/design.md §6.2).
 *
 * Started with the GUI (an auto-start interface of the plugin). The render's
 * image is shown with Map Scalars off, its RGB array being the picture, yet
 * ParaView's Apply adds a colour bar for every coloured representation
 * ("RGB Magnitude"), describing a map the image does not use. A colour bar
 * ParaView adds to an Opal Image View whose shown representations of that
 * map all draw their colours unmapped is hidden again at once; one the user
 * shows later stays.
 */
#pragma once

#include <QObject>

class pqRepresentation;
class pqScalarBarRepresentation;

class pqOpalTrueColourImages : public QObject
{
  Q_OBJECT

public:
  pqOpalTrueColourImages() = default;
  ~pqOpalTrueColourImages() override = default;

  void startup();
  void shutdown() {}

private:
  void onRepresentationAdded(pqRepresentation* representation);
  // Hides the bar where it describes only unmapped, true-colour images.
  static void hideIfTrueColour(pqScalarBarRepresentation* bar);
};
