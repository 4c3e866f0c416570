// The volume the render reads: three of the model's voxel fields (docs/design.md
// §2), x fastest, and the domain table the diffraction needs. Plain data over
// arrays the caller owns.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

class DomainLayout;

// One diffraction domain as the render sees it.
struct RenderDomain
{
  std::array<float, 3> LatticeNormal{ 0.0f, 1.0f, 0.0f }; // FCC (111) plane normal, y >= 0
  float PlaneSpacing = 0.0f;                              // d in nm (eq. 3)
  // The lattice orientation (w, x, y, z): crystal frame -> model frame, taking
  // [111]/sqrt(3) to LatticeNormal (docs/design.md §2.4, the fcc planes of §7.2).
  std::array<float, 4> Orientation{ 1.0f, 0.0f, 0.0f, 0.0f };
};

// The most voxels a render reads: the device holds a voxel's index in 32 bits,
// 2^32 - 1 meaning none (docs/design.md §3.7).
constexpr std::uint64_t MostRenderedVoxels = 0xffffffffu;
// The most voxels of a layer y (x by z) a render reads: the light's sweep
// takes a layer's voxels as one signed dispatch (only a grid one voxel high
// reaches it within MostRenderedVoxels).
constexpr std::uint64_t MostLayerVoxels = 0x7fffffffu;

// The sums the render takes over every voxel of the medium: whether any
// voxel absorbs, the coloured absorption exponent and each domain's voxels.
// Where a process holds only some layers of the medium, each sums its own
// layers and the processes add them up (docs/design.md §8.1).
struct MediumSums
{
  bool Absorbs = false;
  float ColouredAbsorptionExponent = 0.0f; // the first absorbing voxel's not 0, in voxel order
  // Per domain: its voxels' indices (i, j, k) summed (whole numbers, exact
  // in double in any order below 2^53, as every grid of at most
  // MostRenderedVoxels voxels keeps them while its axes are below 2^21), and their count.
  std::vector<std::array<double, 3>> DomainIndexSums;
  std::vector<std::uint64_t> DomainVoxels;

  // Adds the sums of layers that follow these (the first coloured exponent stays).
  void add(const MediumSums& later);
};

// The medium of some layers z alone: ScatteringCoefficient, DomainId and the
// absorption pair hold layers [first, end), from their first value, while
// SurfaceDistance is whole. A process of a march shared by processes reads
// no more (docs/design.md §8.1); `Whole` gives the whole medium's sums.
struct HeldMedium
{
  std::pair<int, int> Layers{ 0, 0 };
  MediumSums Whole;
};

struct RenderVolume
{
  std::array<int, 3> Dimensions{};
  std::array<double, 3> Origin{};  // centre of voxel (0, 0, 0), mm
  std::array<double, 3> Spacing{}; // mm
  const float* ScatteringCoefficient = nullptr; // 1/mm at 550 nm
  const std::int32_t* DomainId = nullptr;       // -1 or an index into Domains
  const float* SurfaceDistance = nullptr;       // mm, negative inside
  // Both or neither (docs/design.md §2.10); neither: nothing absorbs (the paper).
  const float* AbsorptionCoefficient = nullptr; // 1/mm at 550 nm
  const float* AbsorptionExponent = nullptr;    // p: mu_a(lambda) = mu_a(550) (550/lambda)^p
  std::vector<RenderDomain> Domains;
  // The crystal of the coupled-wave model (docs/design.md §7.2): the model's
  // SphereRefractiveIndex and MatrixRefractiveIndex.
  double SphereRefractiveIndex = 1.45;
  double MatrixRefractiveIndex = 1.33;
  // Where set, the medium's arrays hold only these layers (else all).
  std::optional<HeldMedium> Held;

  std::size_t voxelCount() const;
  std::size_t layerVoxels() const;
  // The whole-grid voxels [first, end) of layers z [first, end).
  std::pair<std::size_t, std::size_t> voxelsOfLayers(std::pair<int, int> layers) const;
  // The layers z the medium's arrays hold: Held's, else all.
  std::pair<int, int> mediumLayers() const;
  // The whole-grid index of the medium's arrays' first value: a voxel i's
  // ScatteringCoefficient is ScatteringCoefficient[i - mediumFirstVoxel()].
  std::size_t mediumFirstVoxel() const;
  // True if any voxel absorbs (of the whole medium, as every process below).
  bool absorbs() const;
  // The exponent of the absorbing voxels whose exponent is not 0 (the body's
  // colour), or 0 if all are grey. The render carries two absorption depths,
  // this exponent's and the grey one (docs/design.md §3.9).
  float colouredAbsorptionExponent() const;
  // Per domain, the mean of its voxels' centres in mm (the grid's centre for
  // a domain no voxel holds): where the light's Bragg shadow table takes the
  // direction to the light (docs/design.md §7.2).
  std::vector<std::array<double, 3>> domainCentres() const;
};

// A domain with this lattice normal and sphere diameter (nm), taken as the
// volume's float arrays hold it, so a table built from a layout and one read
// back from a volume's field data are the same.
// orientation (w, x, y, z) as latticeQuaternion gives it.
RenderDomain renderDomain(
  const std::array<double, 3>& normal, double particleDiameter, const std::array<double, 4>& orientation);

// Domain i of the layout as RenderDomain i.
std::vector<RenderDomain> renderDomains(const DomainLayout& layout);

// The medium's sums over layers z [first, end) of `volume`, which holds
// them; domains outside the table are left out (validate refuses them).
MediumSums sumMedium(const RenderVolume& volume, std::pair<int, int> layers);

// Empty if the render can read the volume, else one sentence naming what is
// wrong: dimensions and spacing positive, origin finite, at most
// MostRenderedVoxels voxels and MostLayerVoxels a layer y (checked before any
// array is read), the three fields
// present, ScatteringCoefficient finite and >= 0, SurfaceDistance finite,
// AbsorptionCoefficient (if any) finite and >= 0 with its AbsorptionExponent
// finite, and at most one exponent other than 0 among the absorbing voxels,
// every DomainId -1 or within the domain table, every domain a finite unit
// normal, a positive plane spacing and a finite unit orientation, the
// crystal's indices within [1, 4). Of a medium held by layers (Held), its
// layers within the grid and the checks of the medium's arrays over them
// alone (each process checks its own; the exponent against the whole's).
std::string validate(const RenderVolume& volume);

} // namespace opal
