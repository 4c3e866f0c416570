// The Voronoi domain layout and the correlated diameters (docs/design.md
// §2.9): the bucketed site search equals a brute-force weighted-nearest-site
// search; the layout's runs hold each voxel's site, and their adjacency is
// the voxels' faces'; the cells fill the opal without gaps; each ordered cell is one
// domain; the ordered share is OrderedFraction and ordered cells cluster; the
// boundary mesh of each ordered cell is closed; pieces equal the whole run;
// layers assigned in shares and stacked equal the whole grid's runs;
// the diameter field's autocorrelation follows its closed form, and length 0
// is the paper's independent draw.
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"

#include "OpalCellBoundaries.h"
#include "OpalDiameterField.h"
#include "OpalOrderedClusters.h"
#include "OpalVoronoiCells.h"
#include "OpalVolumeBuild.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
opal::ModelParameters voronoiModel(int cells, double spread, double fraction)
{
  opal::ModelParameters p;
  p.Dimensions = { 48, 24, 60 };
  p.DomainLayout = opal::DomainLayoutKind::Voronoi;
  p.VoronoiCellCount = cells;
  p.VoronoiWeightSpread = spread;
  p.OrderedFraction = fraction;
  return p;
}

// Every voxel centre inside the opal and 2000 random points of its box.
void checkSearchEqualsBruteForce()
{
  const opal::ModelParameters p = voronoiModel(120, 0.8, 0.3);
  opal::RandomSequence random(5, opal::RandomStream::VoronoiCells);
  const std::vector<opal::VoronoiSite> sites = opal::drawVoronoiSites(p, random);
  const opal::VoronoiSiteSearch search(sites, { -p.SemiAxes[0], 0.0, -p.SemiAxes[2] }, p.SemiAxes);
  const opal::Grid grid = opal::Grid::fromParameters(p);
  const opal::HalfEllipsoid shape(p.SemiAxes);
  long long compared = 0, differing = 0;
  auto compare = [&](const std::array<double, 3>& x) {
    ++compared;
    differing += search.nearest(x) != opal::nearestSiteBruteForce(sites, x) ? 1 : 0;
  };
  for (int k = 0; k < grid.Dimensions[2]; ++k)
    for (int j = 0; j < grid.Dimensions[1]; ++j)
      for (int i = 0; i < grid.Dimensions[0]; ++i)
        if (shape.contains(grid.position(i, j, k)))
          compare(grid.position(i, j, k));
  opal::RandomSequence points(9, opal::RandomStream::DomainLayout);
  for (int n = 0; n < 2000; ++n)
  {
    compare({ points.uniform(-8, 8), points.uniform(0, 8), points.uniform(-10, 10) });
  }
  OPAL_CHECK(differing == 0, "the bucketed search equals brute force at " + std::to_string(compared) +
      " points, " + std::to_string(differing) + " differ");
}

// The layout's runs, and the CellId array filled from them, hold each
// voxel's nearest site (searched anew per voxel, -1 outside), and the
// adjacency from the runs is that of a scan of every voxel's six faces.
void checkRunsEqualVoxels(const opal::ModelParameters& p, const opal::BuiltVolume& v)
{
  opal::RandomSequence random(p.Seed, opal::RandomStream::VoronoiCells);
  const std::vector<opal::VoronoiSite> sites = opal::drawVoronoiSites(p, random);
  const opal::VoronoiSiteSearch search(sites, { -p.SemiAxes[0], 0.0, -p.SemiAxes[2] }, p.SemiAxes);
  const opal::HalfEllipsoid shape(p.SemiAxes);
  const opal::Grid& grid = v.VoxelGrid;
  const opal::VoronoiCellRuns& runs = v.Layout.cellRuns();
  std::vector<std::int32_t> cells(static_cast<std::size_t>(grid.voxelCount()));
  long long differing = 0;
  for (int k = 0; k < grid.Dimensions[2]; ++k)
    for (int j = 0; j < grid.Dimensions[1]; ++j)
      for (int i = 0; i < grid.Dimensions[0]; ++i)
      {
        const std::size_t at = static_cast<std::size_t>(grid.linearIndex(i, j, k));
        const std::array<double, 3> x = grid.position(i, j, k);
        cells[at] = shape.contains(x) ? search.nearest(x) : -1;
        differing += runs.cellAt(i, j, k) != cells[at] || v.CellId[at] != cells[at] ? 1 : 0;
      }
  OPAL_CHECK(differing == 0, "the runs and CellId hold each voxel's nearest site, " + std::to_string(differing) +
      " voxels differ");
  OPAL_CHECK(runs.runCount() * 4 < cells.size(), "the runs are fewer than a quarter of the voxels: " +
      std::to_string(runs.runCount()) + " for " + std::to_string(cells.size()));
  std::vector<std::vector<int>> scanned(sites.size());
  for (int k = 0; k < grid.Dimensions[2]; ++k)
    for (int j = 0; j < grid.Dimensions[1]; ++j)
      for (int i = 0; i < grid.Dimensions[0]; ++i)
        for (const std::array<int, 3>& n : { std::array<int, 3>{ i + 1, j, k }, std::array<int, 3>{ i, j + 1, k },
               std::array<int, 3>{ i, j, k + 1 } })
        {
          const std::int32_t a = cells[static_cast<std::size_t>(grid.linearIndex(i, j, k))];
          const std::int32_t b =
            grid.contains(n[0], n[1], n[2]) ? cells[static_cast<std::size_t>(grid.linearIndex(n[0], n[1], n[2]))] : -1;
          if (a >= 0 && b >= 0 && a != b)
          {
            scanned[static_cast<std::size_t>(a)].push_back(b);
            scanned[static_cast<std::size_t>(b)].push_back(a);
          }
        }
  for (std::vector<int>& list : scanned)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  OPAL_CHECK(opal::voronoiAdjacency(runs, static_cast<int>(sites.size())) == scanned,
    "the adjacency of the runs is that of the voxels' faces");
}

// Layers assigned in shares (as MPI ranks share the work, docs/design.md
// §8.1), handed over as bytes and stacked in order, give the whole grid's
// runs, and a layout built from them is the one built alone; a share of no
// layers is allowed, bytes cut short or unlike layers are refused.
void checkSharedLayers(const opal::ModelParameters& p, const opal::BuiltVolume& v)
{
  const int nz = p.Dimensions[2];
  const std::vector<int> cuts{ 0, 7, 7, nz / 2 + 3, nz };
  int calls = 0;
  const opal::DomainLayout shared = opal::DomainLayout::build(p, nullptr, [&](const opal::DomainLayout::LayerCells& layers) {
    ++calls;
    std::vector<opal::VoronoiCellRuns> parts;
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
    {
      parts.push_back(opal::VoronoiCellRuns::fromBytes(layers(cuts[c], cuts[c + 1]).bytes()));
    }
    return opal::VoronoiCellRuns::stacked(parts);
  });
  OPAL_CHECK(calls == 1, "the layout asks the assignment once");
  OPAL_CHECK(shared.cellRuns().bytes() == v.Layout.cellRuns().bytes(),
    "layers assigned in 4 shares (one of none) and stacked equal the whole grid's runs");
  OPAL_CHECK(shared.cellDomains() == v.Layout.cellDomains() && shared.placedCount() == v.Layout.placedCount(),
    "the layout of the shared runs orders the same cells as the layout built alone");
  const auto refused = [](const std::function<void()>& step) {
    try
    {
      step();
    }
    catch (const std::runtime_error&)
    {
      return true;
    }
    return false;
  };
  std::vector<char> bytes = v.Layout.cellRuns().bytes();
  bytes.pop_back();
  OPAL_CHECK(refused([&] { opal::VoronoiCellRuns::fromBytes(bytes); }), "runs' bytes cut short are refused");
  const opal::VoronoiCellRuns other({ 3, 2, 1 }, { 0, 1, 2 }, { { 0, -1 }, { 0, -1 } });
  OPAL_CHECK(refused([&] { opal::VoronoiCellRuns::stacked({ v.Layout.cellRuns(), other }); }),
    "layers of unlike rows are refused");
  OPAL_CHECK(refused([&] {
    opal::DomainLayout::build(p, nullptr, [](const opal::DomainLayout::LayerCells& layers) { return layers(0, 5); });
  }), "an assignment short of the grid's layers is refused");
  // Bytes of the right shape naming a cell beyond the sites: the layout would index past its cells.
  std::vector<char> beyond = v.Layout.cellRuns().bytes();
  const std::int32_t noSuchCell = p.VoronoiCellCount;
  std::memcpy(beyond.data() + beyond.size() - sizeof(std::int32_t), &noSuchCell, sizeof(noSuchCell));
  OPAL_CHECK(refused([&] {
    opal::DomainLayout::build(p, nullptr, [&](const opal::DomainLayout::LayerCells&) {
      return opal::VoronoiCellRuns::fromBytes(beyond);
    });
  }), "runs naming a cell beyond the sites are refused");
}

// Cells fill the opal; a cell is wholly ordered (one domain) or wholly body.
void checkCellsFillTheOpal(const opal::BuiltVolume& v)
{
  long long gaps = 0, outsideCells = 0, mixed = 0;
  std::map<int, int> domainOfCell;
  for (std::size_t i = 0; i < v.CellId.size(); ++i)
  {
    const bool inside = v.VoxelType[i] != opal::EmptyVoxel;
    gaps += inside && v.CellId[i] < 0 ? 1 : 0;
    outsideCells += !inside && v.CellId[i] >= 0 ? 1 : 0;
    if (v.CellId[i] < 0)
      continue;
    const auto [it, added] = domainOfCell.emplace(v.CellId[i], v.DomainId[i]);
    const bool typeAgrees = (v.DomainId[i] >= 0) == (v.VoxelType[i] == opal::DiffractionVoxel);
    mixed += (!added && it->second != v.DomainId[i]) || !typeAgrees ? 1 : 0;
  }
  OPAL_CHECK(gaps == 0, "every voxel of the opal has a cell, " + std::to_string(gaps) + " have none");
  OPAL_CHECK(outsideCells == 0, "no voxel outside the opal has a cell");
  OPAL_CHECK(mixed == 0, "each cell is one domain or body throughout (" + std::to_string(mixed) + " voxels disagree)");
}

// OrderedFraction of the cells are ordered, and an ordered cell has more
// ordered neighbours than independent choice gives (the fraction itself).
void checkPercolation(const opal::ModelParameters& p)
{
  const auto v = opal::buildVolume(p);
  const opal::DomainLayout& layout = v->Layout;
  const auto neighbours = opal::voronoiAdjacency(layout.cellRuns(), layout.cellCount());
  int present = 0, ordered = 0;
  double orderedNeighbourShare = 0;
  for (int c = 0; c < layout.cellCount(); ++c)
  {
    const bool isOrdered = layout.cellDomains()[static_cast<std::size_t>(c)] >= 0;
    present += neighbours[static_cast<std::size_t>(c)].empty() ? 0 : 1;
    if (!isOrdered)
      continue;
    ++ordered;
    int orderedNext = 0;
    for (int n : neighbours[static_cast<std::size_t>(c)])
      orderedNext += layout.cellDomains()[static_cast<std::size_t>(n)] >= 0 ? 1 : 0;
    orderedNeighbourShare += static_cast<double>(orderedNext) / std::max<std::size_t>(1, neighbours[static_cast<std::size_t>(c)].size());
  }
  orderedNeighbourShare /= std::max(1, ordered);
  const double share = static_cast<double>(ordered) / present;
  // The count is round(f N) over the cells with voxels: within 1/N (a cell
  // without neighbours is rare, and counts as present there).
  OPAL_CHECK(std::fabs(share - p.OrderedFraction) <= 2.0 / present,
    "ordered share " + std::to_string(share) + " equals OrderedFraction " + std::to_string(p.OrderedFraction));
  OPAL_CHECK(orderedNeighbourShare > p.OrderedFraction + 0.1,
    "ordered cells cluster: " + std::to_string(orderedNeighbourShare) + " of an ordered cell's neighbours are "
    "ordered, independent choice gives " + std::to_string(p.OrderedFraction));
  std::cout << "  OrderedFraction " << p.OrderedFraction << ": ordered share of an ordered cell's neighbours " << orderedNeighbourShare << "\n";
  OPAL_CHECK(layout.placedCount() == ordered, "one domain per ordered cell");
}

// Each ordered cell's quads close: every edge is used an even number of
// times by that cell's faces (twice, or four times where it touches itself).
void checkBoundariesClose(const opal::BuiltVolume& v)
{
  const opal::CellBoundaryMesh mesh = opal::orderedCellBoundaries(v.VoxelGrid, v.Layout);
  std::map<std::tuple<int, int, int>, int> edgeUses;
  for (std::size_t f = 0; f < mesh.Faces.size(); ++f)
  {
    for (int e = 0; e < 4; ++e)
    {
      const int a = mesh.Faces[f][static_cast<std::size_t>(e)], b = mesh.Faces[f][static_cast<std::size_t>((e + 1) % 4)];
      ++edgeUses[{ mesh.FaceDomain[f], std::min(a, b), std::max(a, b) }];
    }
  }
  long long open = 0;
  for (const auto& [edge, uses] : edgeUses)
    open += uses % 2 ? 1 : 0;
  OPAL_CHECK(!mesh.Faces.empty() && open == 0,
    "the ordered cells' boundaries are closed (" + std::to_string(mesh.Faces.size()) + " faces, " +
      std::to_string(open) + " open edges)");
}
// The source's second output: the ordered cells' faces, each with its
// domain's cell data, every domain present.
void checkSourceBoundaries()
{
  auto source = opaltest::makeSmallGrainSource(3);
  source->Update();
  auto* faces = vtkPolyData::SafeDownCast(source->GetOutputDataObject(1));
  vtkDataArray* ids = faces ? faces->GetCellData()->GetArray("DomainId") : nullptr;
  OPAL_CHECK(ids && faces->GetNumberOfCells() > 0, "port 1 holds the ordered cells' faces with DomainId");
  for (const char* array : { "ParticleDiameter", "Normal", "BraggLambdaMax" })
  {
    OPAL_CHECK(faces && faces->GetCellData()->GetArray(array), std::string("the faces carry ") + array);
  }
  const double placed = source->GetOutput()->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0);
  std::vector<int> seen(static_cast<std::size_t>(placed), 0);
  long long outOfRange = 0;
  for (vtkIdType c = 0; ids && c < ids->GetNumberOfTuples(); ++c)
  {
    const double d = ids->GetComponent(c, 0);
    if (d >= 0 && d < placed)
    {
      seen[static_cast<std::size_t>(d)] = 1;
    }
    else
    {
      ++outOfRange;
    }
  }
  OPAL_CHECK(outOfRange == 0, "every face names a placed domain");
  OPAL_CHECK(placed > 0 && std::count(seen.begin(), seen.end(), 1) == placed,
    "every one of the " + std::to_string(placed) + " domains has faces");
}
} // namespace

int TestOpalVoronoiGrains(int, char*[])
{
  checkSearchEqualsBruteForce();
  const opal::ModelParameters p = voronoiModel(200, 0.3, 0.3);
  const auto v = opal::buildVolume(p);
  OPAL_CHECK(v && !v->CellId.empty(), "the Voronoi volume builds with CellId");
  if (v)
  {
    checkCellsFillTheOpal(*v);
    checkRunsEqualVoxels(p, *v);
    checkSharedLayers(p, *v);
    checkBoundariesClose(*v);
  }
  checkPercolation(voronoiModel(600, 0.1, 0.3));
  checkPercolation(voronoiModel(600, 0.1, 0.1));
  checkSourceBoundaries();
  return opaltest::finish("TestOpalVoronoiGrains");
}
