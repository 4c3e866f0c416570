#include "OpalCellBoundaries.h"

#include <algorithm>
#include <utility>

namespace opal
{

namespace
{
// Voxel corners are the nodes of a lattice one larger than the grid each
// way; each gets its point the first time a face uses it. The faces of a
// layer of voxels (z = k) use the corner planes k and k + 1 only, and the
// layers go in order, so two dense planes (much faster than hashing) give
// the ids a table of every corner would, for a plane's bytes instead of the
// volume's.
class CornerIndex
{
public:
  CornerIndex(const Grid& grid, CellBoundaryMesh& mesh)
    : VoxelGrid(grid)
    , Mesh(mesh)
    , PlaneSize(static_cast<std::size_t>(grid.Dimensions[0] + 1) * static_cast<std::size_t>(grid.Dimensions[1] + 1))
    , Planes{ std::vector<int>(PlaneSize, -1), std::vector<int>(PlaneSize, -1) }
  {
  }

  // The faces of voxel layer k come next: planes k and k + 1.
  void startLayer(int k)
  {
    if (k == this->Low + 1)
    {
      std::swap(this->Planes[0], this->Planes[1]);
      std::fill(this->Planes[1].begin(), this->Planes[1].end(), -1);
      this->Low = k;
    }
  }

  int at(const std::array<int, 3>& corner)
  {
    const std::size_t key =
      static_cast<std::size_t>(corner[0]) + (this->VoxelGrid.Dimensions[0] + 1ULL) * static_cast<std::size_t>(corner[1]);
    int& id = this->Planes[static_cast<std::size_t>(corner[2] - this->Low)][key];
    if (id < 0)
    {
      id = static_cast<int>(this->Mesh.Points.size());
      std::array<double, 3> position{};
      for (int a = 0; a < 3; ++a)
      {
        position[a] = this->VoxelGrid.Origin[a] + (corner[a] - 0.5) * this->VoxelGrid.Spacing[a];
      }
      this->Mesh.Points.push_back(position);
    }
    return id;
  }

private:
  const Grid& VoxelGrid;
  CellBoundaryMesh& Mesh;
  std::size_t PlaneSize;
  std::array<std::vector<int>, 2> Planes; // corner planes Low and Low + 1
  int Low = 0;
};

// The face of voxel ijk on the side `sign` (+1 or -1) of axis a, facing out.
void addFace(CornerIndex& corners, CellBoundaryMesh& mesh, const std::array<int, 3>& ijk, int a, int sign, int domain)
{
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  std::array<int, 3> base = ijk;
  base[a] += sign > 0 ? 1 : 0;
  std::array<int, 4> face{};
  const int du[4] = { 0, 1, 1, 0 }, dv[4] = { 0, 0, 1, 1 };
  for (int c = 0; c < 4; ++c)
  {
    std::array<int, 3> corner = base;
    corner[u] += du[c];
    corner[v] += dv[c];
    face[static_cast<std::size_t>(c)] = corners.at(corner);
  }
  if (sign < 0)
  {
    std::swap(face[1], face[3]); // u x v points along +a: reversed, it faces -a
  }
  mesh.Faces.push_back(face);
  mesh.FaceDomain.push_back(domain);
}

// A row's runs along x.
struct RowRuns
{
  const VoronoiCellRuns::Run* Begin;
  const VoronoiCellRuns::Run* End;
};

// Whether voxel i + sign of the row (i in `run`, which ends before x = end)
// lies in the run's cell: inside the run, or in a neighbouring run of the
// same cell; no search, as the row's runs are at hand.
bool besideAlongRow(const RowRuns& row, const VoronoiCellRuns::Run* run, int end, int i, int sign)
{
  if (i + sign >= run->FirstX && i + sign < end)
  {
    return true;
  }
  if (sign < 0)
  {
    return run != row.Begin && run[-1].Cell == run->Cell;
  }
  return run + 1 != row.End && run[1].Cell == run->Cell;
}

// Whether the voxel beside `ijk` on the side `sign` of axis a lies in the
// cell of `run` (looked up among its row's runs).
bool besideInCell(const Grid& grid, const VoronoiCellRuns& cells, const VoronoiCellRuns::Run* run,
  const std::array<int, 3>& ijk, int a, int sign)
{
  std::array<int, 3> next = ijk;
  next[a] += sign;
  return grid.contains(next[0], next[1], next[2]) && cells.cellAt(next[0], next[1], next[2]) == run->Cell;
}
} // namespace

CellBoundaryMesh orderedCellBoundaries(const Grid& grid, const DomainLayout& layout)
{
  CellBoundaryMesh mesh;
  if (!layout.hasCells())
  {
    return mesh;
  }
  CornerIndex corners(grid, mesh);
  const VoronoiCellRuns& cells = layout.cellRuns();
  for (int k = 0; k < grid.Dimensions[2]; ++k)
  {
    corners.startLayer(k);
    for (int j = 0; j < grid.Dimensions[1]; ++j)
    {
      const RowRuns row{ cells.rowBegin(j, k), cells.rowEnd(j, k) };
      for (const VoronoiCellRuns::Run* run = row.Begin; run != row.End; ++run)
      {
        const int domain = layout.cellDomain(run->Cell);
        const int end = cells.runEnd(run, row.End);
        for (int i = run->FirstX; domain >= 0 && i < end; ++i)
        {
          const std::array<int, 3> ijk{ i, j, k };
          for (int a = 0; a < 3; ++a)
          {
            for (int sign : { -1, 1 })
            {
              const bool sameCell =
                a == 0 ? besideAlongRow(row, run, end, i, sign) : besideInCell(grid, cells, run, ijk, a, sign);
              if (!sameCell)
              {
                addFace(corners, mesh, ijk, a, sign, domain);
              }
            }
          }
        }
      }
    }
  }
  return mesh;
}

} // namespace opal
