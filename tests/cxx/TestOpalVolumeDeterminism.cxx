// Determinism and piece invariance (docs/design.md §2.7): the same seed gives
// identical arrays, another seed different ones, and any split of the extent
// into pieces gives exactly the whole run's values.
#include "OpalTestVolumes.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <string>

int TestOpalVolumeDeterminism(int, char*[])
{
  using namespace opaltest;
  auto first = makeSmallSource(7);
  first->Update();
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(first->GetOutput());

  auto again = makeSmallSource(7);
  again->Update();
  for (const char* name : volumeArrayNames())
  {
    OPAL_CHECK(countDifferences(whole, again->GetOutput(), name) == 0,
      std::string("same seed reproduces ") + name);
  }

  auto other = makeSmallSource(8);
  other->Update();
  OPAL_CHECK(countDifferences(whole, other->GetOutput(), "ParticleDiameter") > 0,
    "another seed changes ParticleDiameter");
  OPAL_CHECK(countDifferences(whole, other->GetOutput(), "DomainId") > 0,
    "another seed changes the domain layout");

  for (int pieces : { 2, 3 })
  {
    long long covered = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      auto source = makeSmallSource(7);
      source->UpdatePiece(piece, pieces, 0);
      vtkImageData* part = source->GetOutput();
      OPAL_CHECK(part->GetNumberOfPoints() < whole->GetNumberOfPoints(),
        "piece " + std::to_string(piece) + " of " + std::to_string(pieces) + " is a proper sub-extent");
      covered += part->GetNumberOfPoints();
      for (const char* name : volumeArrayNames())
      {
        OPAL_CHECK(countDifferences(whole, part, name) == 0,
          std::string(name) + " of piece " + std::to_string(piece) + " of " + std::to_string(pieces) +
            " equals the whole run");
      }
    }
    OPAL_CHECK(covered >= whole->GetNumberOfPoints(), "the pieces cover the volume");
  }
  return finish("TestOpalVolumeDeterminism");
}
