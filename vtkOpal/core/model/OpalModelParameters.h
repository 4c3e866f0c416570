// Every parameter of the volumetric opal model (paper §3-4, docs/design.md §2),
// with the paper's values where it gives them and documented choices where
// it does not. Plain data, no VTK types.
#pragma once

#include "OpalModelParameterTable.h"
#include "OpalParameterRow.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace opal
{

// How the crystal domains are laid out (docs/design.md §2.4, §2.9): the paper's
// flat polygons, or three-dimensional grains of a weighted Voronoi
// tessellation whose ordered cells are percolation clusters (§2.6).
enum class DomainLayoutKind : int
{
  Polygons = 0,
  Voronoi = 1,
};

struct ModelParameters
{
  std::array<int, 3> Dimensions{ 160, 80, 200 };         // voxels (x, y, z), paper §7
  std::array<double, 3> PhysicalSize{ 16.0, 8.0, 20.0 }; // mm, paper §7
  std::array<double, 3> SemiAxes{ 8.0, 8.0, 10.0 };      // mm, half-ellipsoid a, b, c
  std::array<double, 2> ScatteringDiameterRange{ 5.0, 50.0 }; // nm, paper §2
  // Silica volume fraction of the scattering body. The paper gives none; 0.2
  // gives mean mu_s(550) ~ 0.34 /mm: milky and translucent over 8 mm.
  double ScatteringVolumeFraction = 0.2;
  int DomainCount = 250;                                   // paper §7
  std::array<int, 2> DomainVertexRange{ 5, 8 };            // polygon vertices
  std::array<double, 2> DomainRadiusRange{ 0.5, 1.5 };     // mm, circumradius
  std::array<double, 2> DomainVertexJitter{ 0.4, 1.0 };    // fraction of the radius
  std::array<double, 2> DomainAngleRange{ 30.0, 170.0 };   // deg, interior angles
  std::array<double, 2> DomainRotationRange{ 0.0, 30.0 };  // deg, tilt of the normal from +y
  std::array<double, 2> DomainDiameterRange{ 250.0, 350.0 }; // nm, fig12
  double RefractiveIndex = 1.45;                           // mu of opal (silica)
  int MaxPlacementAttempts = 1000;                         // per domain
  DomainLayoutKind DomainLayout = DomainLayoutKind::Polygons;
  int VoronoiCellCount = 1000;        // Voronoi sites in the opal
  double VoronoiWeightSpread = 0.2;   // mm, additive weights uniform in [0, spread]
  double OrderedFraction = 0.3;       // share of the Voronoi cells that are crystal domains
  // mm: the scattering diameters as a smooth random field of this length
  // (value noise on a lattice of this spacing); 0: independent voxels (the paper).
  double DiameterCorrelationLength = 0.0;
  // Beyond the paper (docs/design.md §2.10), each 0 by default: the paper's
  // opal absorbs nothing and its domains do not scatter.
  double BodyAbsorption = 0.0;         // 1/mm at 550 nm, mu_a(lambda) = mu_a(550) (550/lambda)^p
  double BodyAbsorptionExponent = 0.0; // p: 0 grey, > 0 absorbs blue (fire opal), < 0 absorbs red
  double BackingThickness = 0.0;       // mm: the opal's voxels with y below it are the backing
  double BackingAbsorption = 0.0;      // 1/mm, grey: the backing's absorption instead of the body's
  double DomainScatteringCoefficient = 0.0; // 1/mm at 550 nm (lambda^-4) in the domain voxels
  // The crystal of the coupled-wave Bragg model (docs/design.md §7.2): close-packed
  // spheres of one index in a matrix of another; only that render model reads them.
  double SphereRefractiveIndex = 1.45; // n_s, silica
  double MatrixRefractiveIndex = 1.33; // n_m, water (hydrated silica in natural opal)
  // [0, 2147483647]: the range VTK's int property, ParaView's and the field
  // data's int array all hold exactly (and the CLI takes).
  int Seed = 1;

  // True if any voxel absorbs: the volume then carries AbsorptionCoefficient.
  bool absorbs() const;

  // Sets the parameters the paper varies between figures; false if the index is unknown.
  bool applyPreset(int presetIndex);
};

// The largest silica volume fraction: close packing of equal spheres.
constexpr double MaxVolumeFraction = 0.74;
// Upper bounds that keep the domain placement finite in time (the paper: 250
// domains of 5-10 vertices).
constexpr int MaxDomainCount = 100000;
constexpr int MaxDomainVertices = 64;
// Every process keeps the sites, their adjacency and each voxel's cell.
constexpr int MaxVoronoiCellCount = 1000000;
// The largest absorption and domain scattering coefficients (1/mm): 1e4 is
// opaque within a tenth of a micrometre, far beyond any voxel.
constexpr double MaxCoefficientPerMm = 1e4;
// The largest |BodyAbsorptionExponent|: (550/380)^12 is 84 times the 550 nm value.
constexpr double MaxAbsorptionExponent = 12.0;

// One row per parameter of OPAL_MODEL_PARAMETERS, in its order.
const std::vector<ParameterRow<ModelParameters>>& modelParameterRows();

// Empty if the parameters are valid, else one sentence naming the parameter:
// finiteness, magnitudes and the rules between parameters first, then every
// row's range.
std::string validate(const ModelParameters& parameters);

// Empty unless the shape spans fewer than two voxels along some axis (the
// opal would be empty or a few voxels: valid, but surely not meant); then a
// warning naming SemiAxes.
std::string smallShapeWarning(const ModelParameters& parameters);

} // namespace opal
