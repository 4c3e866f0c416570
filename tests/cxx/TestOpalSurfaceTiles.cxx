// SurfaceDistance's tiles (core/render/OpalSurfaceTiles.h, docs/design.md
// §3.4), which the highlight pass reads: a held tile holds the field's very
// values, and a tile standing as one bound bounds the trilinear read
// everywhere in its cells, with its sign, up to the grid's box (the outermost
// cells' reads continue half a cell beyond the centres). The read is
// VolumeGeometry's host interpolant, independent of the tiles' own nodes;
// the volumes are an exact sphere's distance on an anisotropic grid, the
// model's cabochon (which touches the grid's top, sides and base) and a
// field of random values that is no distance at all.
#include "OpalSurfaceTiles.h"
#include "OpalTestVolumes.h"
#include "OpalVolumeGeometry.h"
#include "vtkOpalRenderInput.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace
{
// A volume whose SurfaceDistance is `values` (the other fields unread here).
struct FieldVolume
{
  std::vector<float> Values;
  opal::RenderVolume Volume;
};

FieldVolume sphereVolume()
{
  FieldVolume f;
  f.Volume.Dimensions = { 33, 17, 41 };
  f.Volume.Origin = { -4.0, -2.0, -5.0 };
  f.Volume.Spacing = { 0.3, 0.45, 0.25 };
  const auto& d = f.Volume.Dimensions;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        const double x = -4.0 + 0.3 * i, y = -2.0 + 0.45 * j, z = -5.0 + 0.25 * k;
        f.Values.push_back(static_cast<float>(std::sqrt(x * x + y * y + z * z) - 3.5));
      }
  f.Volume.SurfaceDistance = f.Values.data();
  return f;
}

FieldVolume randomVolume()
{
  FieldVolume f;
  f.Volume.Dimensions = { 19, 2, 23 };
  f.Volume.Origin = { 0.0, 0.0, 0.0 };
  f.Volume.Spacing = { 0.1, 0.1, 0.1 };
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-0.5f, 3.0f);
  f.Values.resize(19 * 2 * 23);
  std::generate(f.Values.begin(), f.Values.end(), [&] { return value(random); });
  f.Volume.SurfaceDistance = f.Values.data();
  return f;
}

// The tile index of the cell a trilinear read at p takes, as the shader finds it.
std::size_t tileOf(const opal::RenderVolume& v, const opal::SurfaceTiles& tiles, const glm::dvec3& p)
{
  std::size_t index = 0, stride = 1;
  for (int a = 0; a < 3; ++a)
  {
    const double g = std::clamp((p[a] - v.Origin[a]) / v.Spacing[a], -0.5, v.Dimensions[a] - 0.5);
    const int c0 = std::clamp(static_cast<int>(std::floor(g)), 0, std::max(v.Dimensions[a] - 2, 0));
    index += stride * static_cast<std::size_t>(c0 / tiles.Cells);
    stride *= static_cast<std::size_t>(tiles.Count[a]);
  }
  return index;
}

// Every held tile's values are the field's at its voxels (clamped to the grid).
void checkHeldValues(const std::string& name, const opal::RenderVolume& v, const opal::SurfaceTiles& tiles)
{
  const int side = tiles.Cells + 1;
  long long wrong = 0;
  for (std::size_t t = 0; t < tiles.tileCount(); ++t)
  {
    if (tiles.Slot[t] < 0)
    {
      continue;
    }
    const std::array<int, 3> tile = { static_cast<int>(t % tiles.Count[0]),
      static_cast<int>((t / tiles.Count[0]) % tiles.Count[1]), static_cast<int>(t / (tiles.Count[0] * tiles.Count[1])) };
    for (int n = 0; n < side * side * side; ++n)
    {
      const int i = std::min(tile[0] * tiles.Cells + n % side, v.Dimensions[0] - 1);
      const int j = std::min(tile[1] * tiles.Cells + (n / side) % side, v.Dimensions[1] - 1);
      const int k = std::min(tile[2] * tiles.Cells + n / (side * side), v.Dimensions[2] - 1);
      const float field = v.SurfaceDistance[i + v.Dimensions[0] * (j + v.Dimensions[1] * static_cast<std::size_t>(k))];
      wrong += tiles.Values[static_cast<std::size_t>(tiles.Slot[t]) * side * side * side + n] != field;
    }
  }
  OPAL_CHECK(wrong == 0, name + ": " + std::to_string(wrong) + " held values differ from the field's");
}

// At random points of the grid's box, the outermost half cells included:
// where the point's tile stands as a bound, the read has its sign and is no
// nearer 0; where the read comes within the near distance of 0, the tile is held.
void checkBounds(const std::string& name, const opal::RenderVolume& v, const opal::SurfaceTiles& tiles)
{
  const opal::VolumeGeometry geometry(v);
  const double near =
    opal::SurfaceTileNearSpacings * std::max({ v.Spacing[0], v.Spacing[1], v.Spacing[2] });
  std::mt19937 random(11);
  long long beyond = 0, unheld = 0, bounded = 0;
  for (int s = 0; s < 200000; ++s)
  {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a)
    {
      std::uniform_real_distribution<double> along(-0.5, v.Dimensions[a] - 0.5);
      p[a] = v.Origin[a] + v.Spacing[a] * along(random);
    }
    const double read = geometry.surfaceDistance(p);
    const std::size_t t = tileOf(v, tiles, p);
    if (tiles.Slot[t] >= 0)
    {
      continue;
    }
    ++bounded;
    const double bound = tiles.Bound[t];
    beyond += (bound > 0.0 ? read < bound : read > bound) ? 1 : 0;
    unheld += std::abs(read) < near;
  }
  OPAL_CHECK(beyond == 0, name + ": " + std::to_string(beyond) + " reads beyond their tile's bound");
  OPAL_CHECK(unheld == 0, name + ": " + std::to_string(unheld) + " reads near the surface in tiles not held");
  OPAL_CHECK(bounded > 0 || tiles.heldTiles() == tiles.tileCount(), name + ": some reads fall in bounded tiles");
}

void checkTiles(const std::string& name, const opal::RenderVolume& v, int cells)
{
  const opal::SurfaceTiles tiles = opal::surfaceTiles(v, cells);
  const std::string what = name + " in tiles of " + std::to_string(cells);
  const auto count = opal::surfaceTileCount(v.Dimensions, cells);
  OPAL_CHECK(tiles.tileCount() == static_cast<std::size_t>(count[0]) * count[1] * count[2] && tiles.Bound.size() == tiles.tileCount(),
    what + ": one slot and one bound per tile");
  for (int a = 0; a < 3; ++a)
  {
    OPAL_CHECK(count[a] * cells >= std::max(v.Dimensions[a] - 1, 1) && (count[a] - 1) * cells < std::max(v.Dimensions[a] - 1, 1),
      what + ": the tiles cover the cells of axis " + std::to_string(a));
  }
  checkHeldValues(what, v, tiles);
  checkBounds(what, v, tiles);
}

// The model's cabochon (which touches the grid's top, sides and base), its
// SurfaceDistance as the render reads it.
struct Cabochon
{
  vtkSmartPointer<vtkOpalSource> Source;
  opal::RenderVolume Volume;
  vtkOpalRenderInput::Storage Storage;
};

std::unique_ptr<Cabochon> cabochon(int scale)
{
  auto c = std::make_unique<Cabochon>();
  c->Source = opaltest::makeSmallSource();
  c->Source->SetDimensions(40 * scale, 20 * scale, 50 * scale);
  OPAL_CHECK(c->Source->GetExecutive()->Update() == 1, "the cabochon builds");
  OPAL_CHECK(vtkOpalRenderInput::Read(c->Source->GetOutput(), c->Volume, c->Storage).empty(), "the cabochon reads");
  return c;
}

// The cabochon's tiles hold, and the share of its tiles held falls as the
// resolution rises (the surface's share of the voxels: 1 / resolution; at the
// highlight's tiles of 8, 61% of the tiles at 80 x 40 x 100 voxels, 34% at
// 160 x 80 x 200, 18% at 320 x 160 x 400).
void checkCabochon()
{
  const auto coarse = cabochon(1);
  for (int cells : { 2, 8 })
  {
    checkTiles("the cabochon", coarse->Volume, cells);
  }
  std::vector<double> held;
  for (int scale : { 2, 4 })
  {
    const opal::SurfaceTiles tiles = opal::surfaceTiles(cabochon(scale)->Volume, 8);
    held.push_back(static_cast<double>(tiles.heldTiles()) / tiles.tileCount());
  }
  OPAL_CHECK(held[1] < 0.7 * held[0], "the tiles held fall from " + std::to_string(held[0]) + " to " +
      std::to_string(held[1]) + " as the resolution doubles, below 0.7 of it");
}
} // namespace

int TestOpalSurfaceTiles(int, char*[])
{
  const FieldVolume sphere = sphereVolume();
  const FieldVolume noise = randomVolume();
  for (int cells : { 1, 3, 8 })
  {
    checkTiles("the sphere", sphere.Volume, cells);
    checkTiles("the random field", noise.Volume, cells);
  }
  checkCabochon();
  return opaltest::finish("TestOpalSurfaceTiles");
}
