/**
 * @class vtkOpalSource
 * @brief The volumetric opal model of Nakajima & Kawai as an image source.
 *
 * Output port 0 is a vtkImageData whose points are voxel centres, with the
 * point arrays VoxelType, ParticleDiameter, Normal, DomainId, BraggLambdaMax,
 * BraggLambdaMin, ScatteringCoefficient and SurfaceDistance (docs/design.md
 * §2.5), CellId with the Voronoi layout, AbsorptionCoefficient and
 * AbsorptionExponent when the model absorbs (§2.10), and the domain table as field data
 * (DomainNormal, DomainParticleDiameter, indexed by DomainId) for the render.
 * Output port 1 is the diffraction-domain layout as polygons with DomainId,
 * ParticleDiameter, Normal and BraggLambdaMax as cell data: one polygon per
 * domain (DomainLayout polygons), or the voxel faces bounding each ordered
 * Voronoi cell (voronoi). Both carry the parameters used and DomainsPlaced as
 * field data.
 *
 * What the volume implies for its render (opal::renderHints: the preset's
 * image size, placement, Bragg model and planes, the model's refractive
 * index) travels in port 0's information (RENDER_HINTS), which every
 * executive copies downstream, so a vtkOpalSpectralRender anywhere below
 * renders what opal-render renders.
 *
 * The source can produce any sub-extent; every value derives from the global
 * voxel index and the seed, so pieces agree exactly with the whole volume.
 *
 * Preset (fig10 ... fig17, harlequin, pinfire, or custom) sets the parameters
 * the paper varies between its figures when it is chosen: DomainDiameterRange,
 * and for harlequin and pinfire DomainLayout, VoronoiCellCount,
 * VoronoiWeightSpread and OrderedFraction. A parameter set afterwards is used
 * (the command line's rule; in ParaView the panel shows the filled values).
 */
#pragma once

#include "vtkImageAlgorithm.h"
#include "vtkOpalModule.h" // for export macro

#include <optional>
#include <string>

class vtkInformationDoubleVectorKey;

class vtkImageData;

namespace opal
{
struct ModelParameters;
class DomainLayout;
}

class VTKOPAL_EXPORT vtkOpalSource : public vtkImageAlgorithm
{
public:
  static vtkOpalSource* New();
  vtkTypeMacro(vtkOpalSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Voxels along x, y, z. Default 160 x 80 x 200 (paper §7).
  vtkSetVector3Macro(Dimensions, int);
  vtkGetVector3Macro(Dimensions, int);
  ///@}

  ///@{
  /// Size of the voxel box in mm. Default 16 x 8 x 20.
  vtkSetVector3Macro(PhysicalSize, double);
  vtkGetVector3Macro(PhysicalSize, double);
  ///@}

  ///@{
  /// Semi-axes a, b, c of the half-ellipsoid in mm. Default 8, 8, 10.
  vtkSetVector3Macro(SemiAxes, double);
  vtkGetVector3Macro(SemiAxes, double);
  ///@}

  ///@{
  /// Diameter range of the scattering silica spheres in nm. Default 5-50.
  vtkSetVector2Macro(ScatteringDiameterRange, double);
  vtkGetVector2Macro(ScatteringDiameterRange, double);
  ///@}

  ///@{
  /// Silica volume fraction of the scattering body, in (0, 0.74]. Default 0.2.
  vtkSetMacro(ScatteringVolumeFraction, double);
  vtkGetMacro(ScatteringVolumeFraction, double);
  ///@}

  ///@{
  /// Number of diffraction domains to place. Default 250 (paper §7).
  vtkSetMacro(DomainCount, int);
  vtkGetMacro(DomainCount, int);
  ///@}

  ///@{
  /// Vertex count range of the domain polygons. Default 5-8.
  vtkSetVector2Macro(DomainVertexRange, int);
  vtkGetVector2Macro(DomainVertexRange, int);
  ///@}

  ///@{
  /// Circumradius range of the domain polygons in mm. Default 0.5-1.5.
  vtkSetVector2Macro(DomainRadiusRange, double);
  vtkGetVector2Macro(DomainRadiusRange, double);
  ///@}

  ///@{
  /// Where on its spoke each vertex may move, as a fraction of the radius. Default 0.4-1.
  vtkSetVector2Macro(DomainVertexJitter, double);
  vtkGetVector2Macro(DomainVertexJitter, double);
  ///@}

  ///@{
  /// Allowed interior angles of the domain polygons in degrees. Default 30-170.
  vtkSetVector2Macro(DomainAngleRange, double);
  vtkGetVector2Macro(DomainAngleRange, double);
  ///@}

  ///@{
  /// Tilt of the domain normals from +y in degrees. Default 0-30.
  vtkSetVector2Macro(DomainRotationRange, double);
  vtkGetVector2Macro(DomainRotationRange, double);
  ///@}

  ///@{
  /// Diameter range of the spheres in the domains in nm (custom preset only). Default 250-350.
  vtkSetVector2Macro(DomainDiameterRange, double);
  vtkGetVector2Macro(DomainDiameterRange, double);
  ///@}

  ///@{
  /// Domain layout (docs/design.md §2.9): 0 the paper's polygons (default), 1
  /// weighted Voronoi grains whose ordered cells are percolation clusters.
  vtkSetMacro(DomainLayout, int);
  vtkGetMacro(DomainLayout, int);
  ///@}

  ///@{
  /// Voronoi sites in the opal. Default 1000.
  vtkSetMacro(VoronoiCellCount, int);
  vtkGetMacro(VoronoiCellCount, int);
  ///@}

  ///@{
  /// Additive weights of the Voronoi sites, uniform in [0, spread] mm. Default 0.2.
  vtkSetMacro(VoronoiWeightSpread, double);
  vtkGetMacro(VoronoiWeightSpread, double);
  ///@}

  ///@{
  /// Share of the Voronoi cells that are crystal domains, in [0, 1]. Default 0.3.
  vtkSetMacro(OrderedFraction, double);
  vtkGetMacro(OrderedFraction, double);
  ///@}

  ///@{
  /// Correlation length in mm of the scattering diameters; 0 (default):
  /// independent voxels, as the paper.
  vtkSetMacro(DiameterCorrelationLength, double);
  vtkGetMacro(DiameterCorrelationLength, double);
  ///@}

  ///@{
  /// Absorption of the body in 1/mm at 550 nm, mu_a(lambda) = mu_a(550)
  /// (550/lambda)^p with p = BodyAbsorptionExponent; domains absorb alike.
  /// Default 0 (the paper). With absorption the volume carries the point
  /// arrays AbsorptionCoefficient and AbsorptionExponent (docs/design.md §2.10).
  vtkSetMacro(BodyAbsorption, double);
  vtkGetMacro(BodyAbsorption, double);
  /// p: 0 (default) grey; > 0 absorbs blue (the orange body of fire opal).
  vtkSetMacro(BodyAbsorptionExponent, double);
  vtkGetMacro(BodyAbsorptionExponent, double);
  /// Height in mm of the backing layer: the opal's voxels with y below it
  /// absorb BackingAbsorption (grey, 1/mm) instead of the body's (the potch
  /// of black opal, the ironstone of boulder opal). Defaults 0.
  vtkSetMacro(BackingThickness, double);
  vtkGetMacro(BackingThickness, double);
  vtkSetMacro(BackingAbsorption, double);
  vtkGetMacro(BackingAbsorption, double);
  /// Scattering coefficient of the domain voxels in 1/mm at 550 nm (lambda^-4
  /// like the body's); 0 (default): the paper's domains do not scatter.
  vtkSetMacro(DomainScatteringCoefficient, double);
  vtkGetMacro(DomainScatteringCoefficient, double);
  /// The crystal of the coupled-wave Bragg model (docs/design.md §7.2):
  /// close-packed spheres of SphereRefractiveIndex (default 1.45, silica) in
  /// a matrix of MatrixRefractiveIndex (default 1.33, water). Only the render's
  /// coupled-wave model reads them (field data).
  vtkSetMacro(SphereRefractiveIndex, double);
  vtkGetMacro(SphereRefractiveIndex, double);
  vtkSetMacro(MatrixRefractiveIndex, double);
  vtkGetMacro(MatrixRefractiveIndex, double);
  ///@}

  ///@{
  /// Refractive index mu of opal. Default 1.45.
  vtkSetMacro(RefractiveIndex, double);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /// Placement (and shape) attempts per domain before it is given up. Default 1000.
  vtkSetMacro(MaxPlacementAttempts, int);
  vtkGetMacro(MaxPlacementAttempts, int);
  ///@}

  ///@{
  /// Seed of every random choice of the model. Default 1.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// 0 custom, 1 fig10, 2 fig11, 3 fig12 (default), 4 fig13, 5 fig15, 6 fig17,
  /// 7 harlequin, 8 pinfire. Choosing a preset sets the parameters it stands
  /// for (DomainDiameterRange; harlequin and pinfire also the Voronoi layout's);
  /// a parameter set afterwards is used. Custom sets nothing.
  void SetPreset(int preset);
  vtkGetMacro(Preset, int);
  /// Chooses the preset by name ("fig12", "custom"); false if the name is unknown.
  bool SetPresetByName(const char* name);
  ///@}

  /// The parameters as the next update will use them.
  opal::ModelParameters GetModelParameters() const;
  /// Sets every model parameter at once; the preset is left as it is.
  void SetModelParameters(const opal::ModelParameters& parameters);

  /// Output information key for the render downstream: opal::packHints of
  /// what the volume implies for its render. Copied downstream in
  /// REQUEST_INFORMATION by every executive (as VTK's meta-data keys are).
  static vtkInformationDoubleVectorKey* RENDER_HINTS();

protected:
  vtkOpalSource();
  ~vtkOpalSource() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Dimensions[3];
  double PhysicalSize[3];
  double SemiAxes[3];
  double ScatteringDiameterRange[2];
  double ScatteringVolumeFraction;
  int DomainCount;
  int DomainVertexRange[2];
  double DomainRadiusRange[2];
  double DomainVertexJitter[2];
  double DomainAngleRange[2];
  double DomainRotationRange[2];
  double DomainDiameterRange[2];
  int DomainLayout;
  int VoronoiCellCount;
  double VoronoiWeightSpread;
  double OrderedFraction;
  double DiameterCorrelationLength;
  double BodyAbsorption;
  double BodyAbsorptionExponent;
  double BackingThickness;
  double BackingAbsorption;
  double DomainScatteringCoefficient;
  double SphereRefractiveIndex;
  double MatrixRefractiveIndex;
  double RefractiveIndex;
  int MaxPlacementAttempts;
  int Seed;
  int Preset;

private:
  vtkOpalSource(const vtkOpalSource&) = delete;
  void operator=(const vtkOpalSource&) = delete;

  // Empty if the parameters are valid, else the message naming the parameter.
  std::string Validate() const;
  // The domain layout (warning when not all domains fit); empty if aborted.
  std::optional<opal::DomainLayout> BuildLayout(const opal::ModelParameters& parameters);
  // Fills the image's extent with the voxel arrays; false if aborted.
  bool FillVolume(vtkImageData* image, const opal::ModelParameters& parameters, const opal::DomainLayout& layout);
};
