// Every model parameter once (docs/design.md §1.1), in the columns of the
// render parameters' table (OpalRenderParameterTable.h):
//   X(Name, Type, Count, Min, Max, Choices, Flag, FromVolume, Description)
// Name is the member of opal::ModelParameters (whose initialiser is the
// default), vtkOpalSource's Set/Get, ParaView's property, the field-data array
// of the volume and, in kebab-case, opal-volume's and opal-render's flag.
// Min and Max are the bounds validate holds every value to; validate's rules
// between parameters and its half-open bounds come on top. The ParaView
// panel's sliders may be narrower (OpalVolume.xml). Plain preprocessor text:
// VTK's wrappers expand it too.
#pragma once

#define OPAL_MODEL_PARAMETERS(X)                                                                          \
  X(Dimensions, int, 3, 1, 100000, "", "--dimensions", 0, "Voxels along x y z (paper section 7)")            \
  X(PhysicalSize, double, 3, 1e-6, 1e4, "", "--physical-size", 0, "Size of the voxel box in mm along x y z") \
  X(SemiAxes, double, 3, 1e-6, 1e4, "", "--semi-axes", 0,                                                   \
    "Half-ellipsoid semi-axes a b c in mm, within the box")                                                 \
  X(ScatteringDiameterRange, double, 2, 1e-3, 1e5, "", "--scattering-diameter-range", 0,                     \
    "Diameters min max of the scattering silica spheres in nm")                                             \
  X(ScatteringVolumeFraction, double, 1, 0, MaxVolumeFraction, "", "--scattering-volume-fraction", 0,        \
    "Silica volume fraction of the milky body, in (0, 0.74]")                                               \
  X(DomainCount, int, 1, 0, MaxDomainCount, "", "--domain-count", 0, "Diffraction domains to place")        \
  X(DomainVertexRange, int, 2, 3, MaxDomainVertices, "", "--domain-vertex-range", 0,                        \
    "Vertex count min max of the domain polygons")                                                         \
  X(DomainRadiusRange, double, 2, 1e-6, 1e4, "", "--domain-radius-range", 0,                                 \
    "Circumradius min max of the domain polygons in mm")                                                   \
  X(DomainVertexJitter, double, 2, 0, 1, "", "--domain-vertex-jitter", 0,                                    \
    "Where on its spoke a vertex may move, min max as a fraction of the radius, in (0, 1]")                 \
  X(DomainAngleRange, double, 2, 0, 180, "", "--domain-angle-range", 0,                                      \
    "Allowed interior angles min max of the domain polygons in degrees")                                    \
  X(DomainRotationRange, double, 2, 0, 90, "", "--domain-rotation-range", 0,                                 \
    "Tilt min max of the domain normals from +y in degrees")                                                \
  X(DomainDiameterRange, double, 2, 1e-3, 1e5, "", "--domain-diameter-range", 0,                             \
    "Diameters min max of the spheres in the domains in nm")                                                \
  X(RefractiveIndex, double, 1, 1, 4, "", "--refractive-index", 0,                                         \
    "Refractive index mu of opal, in [1, 4) (also the render's)")                                          \
  X(MaxPlacementAttempts, int, 1, 1, 100000, "", "--max-placement-attempts", 0,                              \
    "Placement (and shape) attempts per domain before it is given up")                                     \
  X(DomainLayout, int, 1, 0, 1, "polygons voronoi", "--domain-layout", 0,                                    \
    "polygons (the paper's) or voronoi (weighted Voronoi grains, ordered cells as percolation clusters)")    \
  X(VoronoiCellCount, int, 1, 1, MaxVoronoiCellCount, "", "--voronoi-cell-count", 0, "Voronoi sites in the opal") \
  X(VoronoiWeightSpread, double, 1, 0, 1e4, "", "--voronoi-weight-spread", 0,                                \
    "Additive weights of the Voronoi sites, uniform in [0, spread] mm")                                     \
  X(OrderedFraction, double, 1, 0, 1, "", "--ordered-fraction", 0,                                           \
    "Share of the Voronoi cells that are crystal domains")                                                  \
  X(DiameterCorrelationLength, double, 1, 0, 1e4, "", "--diameter-correlation-length", 0,                    \
    "Correlation length of the scattering diameters in mm, 0 or at least 1e-6 (0: independent voxels)")     \
  X(BodyAbsorption, double, 1, 0, MaxCoefficientPerMm, "", "--body-absorption", 0,                           \
    "Absorption of the body in 1/mm at 550 nm, mu_a(550) (550/lambda)^p")                                   \
  X(BodyAbsorptionExponent, double, 1, -MaxAbsorptionExponent, MaxAbsorptionExponent, "",                    \
    "--body-absorption-exponent", 0, "p: 0 grey, > 0 absorbs blue (fire opal), < 0 absorbs red")            \
  X(BackingThickness, double, 1, 0, 1e4, "", "--backing-thickness", 0,                                       \
    "Height in mm of the backing layer (at most the box's): the opal's voxels below absorb BackingAbsorption") \
  X(BackingAbsorption, double, 1, 0, MaxCoefficientPerMm, "", "--backing-absorption", 0,                     \
    "Grey absorption of the backing layer in 1/mm")                                                         \
  X(DomainScatteringCoefficient, double, 1, 0, MaxCoefficientPerMm, "", "--domain-scattering-coefficient", 0, \
    "Scattering coefficient of the domain voxels in 1/mm at 550 nm (lambda^-4)")                            \
  X(SphereRefractiveIndex, double, 1, 1, 4, "", "--sphere-refractive-index", 0,                              \
    "Index of the crystal's spheres, in [1, 4) (the coupled-wave model's; silica)")                         \
  X(MatrixRefractiveIndex, double, 1, 1, 4, "", "--matrix-refractive-index", 0,                              \
    "Index of the matrix between them, in [1, 4) (water)")                                                  \
  X(Seed, int, 1, 0, 2147483647, "", "--seed", 0,                                                           \
    "Seed of every random choice of the model, a whole number in [0, 2147483647]")
