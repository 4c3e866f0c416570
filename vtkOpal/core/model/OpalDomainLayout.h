// The diffraction domains: the paper's (§3.2) jittered regular polygons,
// tilted, spun and moved into the opal, rasterised as one-voxel-thick naive
// digital planes; or the ordered cells of a weighted Voronoi tessellation
// (docs/design.md §2.9). The list depends only on the parameters and the
// seed, so every process computes the same one.
#pragma once

#include "OpalGrid.h"
#include "OpalModelParameters.h"
#include "OpalVoronoiCells.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace opal
{

struct Domain
{
  int Id = -1;
  std::vector<std::array<double, 3>> Vertices; // world coordinates, mm (none for a Voronoi cell)
  std::array<double, 3> Normal{}; // FCC (111) lattice-plane normal, y >= 0
  double ParticleDiameter = 0;    // nm
  double LatticeSpin = 0;         // radians about Normal: the lattice's turn (docs/design.md §2.4, step 6)
};

// The domain's lattice orientation as a unit quaternion (w, x, y, z): the
// rotation from the crystal's cubic frame to the model frame that stands
// [111]/sqrt(3) on Normal and turns it by LatticeSpin (latticeOrientation).
std::array<double, 4> latticeQuaternion(const Domain& domain);

// One diffraction voxel: its global linear index and its domain.
struct DomainVoxel
{
  std::int64_t Index;
  int DomainId;
  bool operator<(const DomainVoxel& other) const { return this->Index < other.Index; }
};

class DomainLayout
{
public:
  // Polygons: places the domains one after another; a domain that finds no
  // free place within MaxPlacementAttempts is skipped (placedCount() tells
  // how many made it). Voronoi: the cells, their percolation and one domain
  // per ordered cell.
  // progress(fraction) is called now and then; returning false aborts the build.
  // Voronoi: `assignment`, where given, assigns the grid's cells, sharing
  // the work (the ranks of an MPI build, docs/design.md §8.1): it calls
  // `layers` for its own layers and returns the whole grid's runs (empty: aborted).
  using LayerCells = std::function<VoronoiCellRuns(int firstLayer, int endLayer)>;
  using CellAssignment = std::function<VoronoiCellRuns(const LayerCells& layers)>;
  static DomainLayout build(const ModelParameters& parameters,
    const std::function<bool(double)>& progress = nullptr, const CellAssignment& assignment = nullptr);

  const std::vector<Domain>& domains() const { return this->Domains; }
  int placedCount() const { return static_cast<int>(this->Domains.size()); }
  int requestedCount() const { return this->Requested; }
  bool aborted() const { return this->Aborted; }

  // Polygons: the diffraction voxels sorted by global index (x fastest), a
  // row of the grid a contiguous run. Empty for Voronoi cells: a voxel's
  // domain is its cell's (cellDomain), and a list of the ordered voxels of
  // the whole grid would cost every process 16 bytes each.
  const std::vector<DomainVoxel>& voxels() const { return this->Voxels; }

  // First diffraction voxel at or after the global index.
  std::vector<DomainVoxel>::const_iterator lowerBound(std::int64_t index) const;

  // Voronoi: the cell of every voxel of the grid (-1 outside the opal), as
  // runs along x, and each cell's domain (-1: disordered). Empty for polygons.
  bool hasCells() const { return !this->CellRuns.empty(); }
  const VoronoiCellRuns& cellRuns() const { return this->CellRuns; }
  const std::vector<int>& cellDomains() const { return this->CellDomains; }
  int cellCount() const { return static_cast<int>(this->CellDomains.size()); }
  // Voronoi: the domain of a cell (-1: none, or no cell).
  int cellDomain(std::int32_t cell) const { return cell >= 0 ? this->CellDomains[static_cast<std::size_t>(cell)] : -1; }

private:
  static DomainLayout buildPolygons(const ModelParameters& parameters, const std::function<bool(double)>& progress);
  // Defined in OpalVoronoiLayout.cxx.
  static DomainLayout buildVoronoi(const ModelParameters& parameters, const std::function<bool(double)>& progress,
    const CellAssignment& assignment);

  std::vector<Domain> Domains;
  std::vector<DomainVoxel> Voxels;
  VoronoiCellRuns CellRuns;
  std::vector<int> CellDomains;
  int Requested = 0;
  bool Aborted = false;
};

// Voxels of the naive digital plane of a convex polygon: along the grid axis
// closest to its normal, each column whose axis crosses the polygon gets the
// one voxel containing the crossing. Exposed for tests. Returns false if a
// crossing falls outside the grid.
// The lattice-plane normal tilted from +y by `tilt` and spun about y by
// `spin` (radians), turned to y >= 0 (step 3 of paper §3.2).
std::array<double, 3> tiltedNormal(double tilt, double spin);

bool rasterisePolygon(const Grid& grid, const std::vector<std::array<double, 3>>& vertices,
  const std::array<double, 3>& normal, std::vector<std::array<int, 3>>& voxels);

} // namespace opal
