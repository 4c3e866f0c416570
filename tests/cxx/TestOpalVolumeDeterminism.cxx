// Determinism and piece invariance (docs/design.md §2.7): the same seed gives
// identical arrays, another seed different ones, and any split of the extent
// into pieces gives exactly the whole run's values: for the paper's polygon
// layout and for Voronoi grains with correlated diameters (CellId too).
#include "OpalTestVolumes.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <functional>
#include <string>
#include <vector>

namespace
{
using SourceMaker = std::function<vtkSmartPointer<vtkOpalSource>(int)>;

void checkDeterminism(const std::string& layout, const SourceMaker& make, const std::vector<std::string>& names)
{
  using namespace opaltest;
  auto first = make(7);
  first->Update();
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(first->GetOutput());

  auto again = make(7);
  again->Update();
  for (const std::string& name : names)
  {
    OPAL_CHECK(countDifferences(whole, again->GetOutput(), name) == 0, layout + ": same seed reproduces " + name);
  }
  auto other = make(8);
  other->Update();
  OPAL_CHECK(countDifferences(whole, other->GetOutput(), "ParticleDiameter") > 0,
    layout + ": another seed changes ParticleDiameter");
  OPAL_CHECK(countDifferences(whole, other->GetOutput(), "DomainId") > 0, layout + ": another seed changes the domains");

  for (int pieces : { 2, 3 })
  {
    long long covered = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      auto source = make(7);
      source->UpdatePiece(piece, pieces, 0);
      vtkImageData* part = source->GetOutput();
      const std::string which = " of piece " + std::to_string(piece) + " of " + std::to_string(pieces);
      OPAL_CHECK(part->GetNumberOfPoints() < whole->GetNumberOfPoints(), layout + which + " is a proper sub-extent");
      covered += part->GetNumberOfPoints();
      for (const std::string& name : names)
      {
        OPAL_CHECK(countDifferences(whole, part, name) == 0, layout + ": " + name + which + " equals the whole run");
      }
    }
    OPAL_CHECK(covered >= whole->GetNumberOfPoints(), layout + ": the pieces cover the volume");
  }
}
} // namespace

int TestOpalVolumeDeterminism(int, char*[])
{
  const auto& arrays = opaltest::volumeArrayNames();
  std::vector<std::string> names(arrays.begin(), arrays.end());
  checkDeterminism("polygons", [](int seed) { return opaltest::makeSmallSource(seed); }, names);
  names.emplace_back("CellId");
  checkDeterminism("voronoi", [](int seed) { return opaltest::makeSmallGrainSource(seed); }, names);
  return opaltest::finish("TestOpalVolumeDeterminism");
}
