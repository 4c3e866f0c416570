// Determinism and piece invariance (docs/design.md §2.7): the same seed gives
// identical arrays, another seed different ones (also on a source that kept
// the old layout), and any split of the extent into pieces, built by one
// source, gives exactly the whole run's values: for the paper's polygon
// layout and for Voronoi grains with correlated diameters (CellId too). A grid
// larger than this machine's memory is refused whole and built by pieces. The
// render's arrays alone (OutputArrays render) equal the whole set's.
#include "OpalTestVolumes.h"

#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

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

  // One source builds every piece of a split: the layout it keeps between
  // pieces (vtkOpalSource) gives the whole run's values.
  for (int pieces : { 2, 3 })
  {
    long long covered = 0;
    auto source = make(7);
    for (int piece = 0; piece < pieces; ++piece)
    {
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
  // A changed setting rebuilds the kept layout.
  auto reseeded = make(7);
  reseeded->Update();
  reseeded->SetSeed(8);
  reseeded->Update();
  OPAL_CHECK(countDifferences(other->GetOutput(), reseeded->GetOutput(), "DomainId") == 0,
    layout + ": a source given another seed lays its domains out anew");
}
// The memory check is the piece's (§2.7, §8.2): 4000^3 voxels (2.4 TB of
// arrays) are refused whole, and a small piece of them builds.
void checkPieceOfHugeGrid()
{
  opaltest::silenceExpectedErrors();
  auto whole = opaltest::makeSmallSource(7);
  whole->SetDimensions(4000, 4000, 4000);
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(whole);
  OPAL_CHECK(!whole->GetExecutive()->Update(), "a 4000^3 grid is refused whole");
  OPAL_CHECK(recorder->anyContains(recorder->Errors, "of memory"), "the refusal names the memory");
  auto source = opaltest::makeSmallSource(7);
  source->SetDimensions(4000, 4000, 4000);
  const int piece[6] = { 1980, 2019, 0, 19, 1980, 2029 };
  source->UpdateExtent(piece);
  OPAL_CHECK(source->GetOutput()->GetNumberOfPoints() == 40 * 20 * 50, "a 40 x 20 x 50 piece of it builds");
}

// OutputArrays render (vtkOpalSource): only the render's arrays, in the
// order the whole set has them, each equal to the whole set's, whole and in
// pieces; the source's scalars are ScatteringCoefficient. Another value is
// refused, named.
void checkRenderArrays(const std::string& layout, const SourceMaker& make)
{
  auto all = make(7);
  all->Update();
  auto render = make(7);
  render->SetOutputArrays(vtkOpalSource::RENDER_ARRAYS);
  render->Update();
  vtkPointData* data = render->GetOutput()->GetPointData();
  const std::vector<std::string> expected{ "DomainId", "ScatteringCoefficient", "SurfaceDistance" };
  std::vector<std::string> names;
  for (int a = 0; a < data->GetNumberOfArrays(); ++a)
  {
    names.emplace_back(data->GetArrayName(a));
  }
  OPAL_CHECK(names == expected, layout + ": render arrays only are DomainId, ScatteringCoefficient, SurfaceDistance");
  OPAL_CHECK(data->GetScalars() && std::string(data->GetScalars()->GetName()) == "ScatteringCoefficient" &&
      vtkImageData::GetScalarType(render->GetOutputInformation(0)) == VTK_FLOAT,
    layout + ": their scalars are ScatteringCoefficient, announced as float");
  for (const std::string& name : expected)
  {
    OPAL_CHECK(opaltest::countDifferences(all->GetOutput(), render->GetOutput(), name) == 0,
      layout + ": the render's " + name + " equals the whole set's");
    render->UpdatePiece(1, 3, 0);
    OPAL_CHECK(opaltest::countDifferences(all->GetOutput(), render->GetOutput(), name) == 0,
      layout + ": piece 1 of 3 of the render's " + name + " equals the whole set's");
    render->UpdatePiece(0, 1, 0);
  }
  opaltest::silenceExpectedErrors();
  auto unknown = make(7);
  unknown->SetOutputArrays(2);
  vtkNew<opaltest::MessageRecorder> recorder;
  recorder->watch(unknown);
  OPAL_CHECK(!unknown->GetExecutive()->Update() && recorder->anyContains(recorder->Errors, "OutputArrays 2"),
    layout + ": OutputArrays 2 is refused, named");
}
} // namespace

int TestOpalVolumeDeterminism(int, char*[])
{
  const auto& arrays = opaltest::volumeArrayNames();
  std::vector<std::string> names(arrays.begin(), arrays.end());
  checkDeterminism("polygons", [](int seed) { return opaltest::makeSmallSource(seed); }, names);
  names.emplace_back("CellId");
  checkDeterminism("voronoi", [](int seed) { return opaltest::makeSmallGrainSource(seed); }, names);
  checkPieceOfHugeGrid();
  checkRenderArrays("polygons", [](int seed) { return opaltest::makeSmallSource(seed); });
  checkRenderArrays("voronoi", [](int seed) { return opaltest::makeSmallGrainSource(seed); });
  return opaltest::finish("TestOpalVolumeDeterminism");
}
