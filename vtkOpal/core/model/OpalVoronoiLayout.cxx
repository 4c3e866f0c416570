// DomainLayout::buildVoronoi (docs/design.md §2.9): the weighted Voronoi
// cells of the opal, their percolation clusters, and one crystal domain per
// ordered cell.
#include "OpalDomainLayout.h"

#include "OpalHalfEllipsoid.h"
#include "OpalOptics.h"
#include "OpalOrderedClusters.h"
#include "OpalRandom.h"
#include "OpalVoronoiCells.h"

#include <stdexcept>

namespace opal
{

namespace
{
// Share of the layout's progress spent assigning voxels to cells.
constexpr double AssignShare = 0.9;

std::vector<std::uint8_t> cellsWithVoxels(const VoronoiCellRuns& cells, int cellCount)
{
  std::vector<std::uint8_t> has(static_cast<std::size_t>(cellCount), 0);
  const std::array<int, 3>& dims = cells.dimensions();
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (const VoronoiCellRuns::Run* run = cells.rowBegin(j, k); run != cells.rowEnd(j, k); ++run)
      {
        if (run->Cell >= 0)
        {
          has[static_cast<std::size_t>(run->Cell)] = 1;
        }
      }
    }
  }
  return has;
}

// An ordered cell's crystal: the (111) normal tilted within
// DomainRotationRange, spun uniformly, and one sphere diameter.
Domain crystalDomain(int id, const ModelParameters& p, RandomSequence& random)
{
  constexpr double DegToRad = Pi / 180.0;
  Domain domain;
  domain.Id = id;
  const double tilt = random.uniform(p.DomainRotationRange[0], p.DomainRotationRange[1]) * DegToRad;
  const double spin = random.uniform(0.0, 360.0) * DegToRad;
  domain.Normal = tiltedNormal(tilt, spin);
  domain.ParticleDiameter = random.uniform(p.DomainDiameterRange[0], p.DomainDiameterRange[1]);
  return domain;
}
} // namespace

DomainLayout DomainLayout::buildVoronoi(
  const ModelParameters& p, const std::function<bool(double)>& progress, const CellAssignment& assignment)
{
  DomainLayout layout;
  const Grid grid = Grid::fromParameters(p);
  const HalfEllipsoid shape(p.SemiAxes);
  RandomSequence random(p.Seed, RandomStream::VoronoiCells);
  const std::vector<VoronoiSite> sites = drawVoronoiSites(p, random);
  const VoronoiSiteSearch search(sites, { -p.SemiAxes[0], 0.0, -p.SemiAxes[2] }, p.SemiAxes);
  const LayerCells layers = [&](int first, int end) {
    return assignVoronoiCells(
      grid, shape, search, { first, end }, [&progress](double f) { return !progress || progress(AssignShare * f); });
  };
  layout.CellRuns = assignment ? assignment(layers) : layers(0, grid.Dimensions[2]);
  if (layout.CellRuns.empty())
  {
    layout.Aborted = true;
    return layout;
  }
  const int cellCount = static_cast<int>(sites.size());
  if (layout.CellRuns.dimensions() != grid.Dimensions || !layout.CellRuns.wellFormed(cellCount))
  {
    throw std::runtime_error("Voronoi cells: the assignment's runs are not the grid's cells.");
  }
  const std::vector<std::uint8_t> ordered = orderedCells(voronoiAdjacency(layout.CellRuns, cellCount),
    cellsWithVoxels(layout.CellRuns, cellCount), p.OrderedFraction, random);
  layout.CellDomains.assign(static_cast<std::size_t>(cellCount), -1);
  for (int c = 0; c < cellCount; ++c)
  {
    if (ordered[static_cast<std::size_t>(c)])
    {
      layout.CellDomains[static_cast<std::size_t>(c)] = static_cast<int>(layout.Domains.size());
      layout.Domains.push_back(crystalDomain(static_cast<int>(layout.Domains.size()), p, random));
    }
  }
  layout.Requested = static_cast<int>(layout.Domains.size());
  return layout;
}

} // namespace opal
