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

#include "OpalModelParameterTable.h" // for OPAL_MODEL_PARAMETERS
#include "vtkImageAlgorithm.h"
#include "vtkOpalModule.h"       // for export macro
#include "vtkOpalTableMacros.h"  // for OPAL_VTK_SET_GET, OPAL_VTK_MEMBER

#include "vtkSmartPointer.h"     // for the layout's polygons

#include <memory>
#include <string>

class vtkInformationDoubleVectorKey;

class vtkImageData;
class vtkMultiProcessController;
class vtkPolyData;

namespace opal
{
struct ModelParameters;
class DomainLayout;
enum class VolumeArrays;
class VolumeFiller;
struct VolumeFields;
}

class VTKOPAL_EXPORT vtkOpalSource : public vtkImageAlgorithm
{
public:
  static vtkOpalSource* New();
  vtkTypeMacro(vtkOpalSource, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Every model parameter of opal::ModelParameters, one Set/Get pair each,
  /// generated from OPAL_MODEL_PARAMETERS (OpalModelParameterTable.h), which
  /// gives each one's default (the paper's, fig12), range and meaning; the
  /// field data of the outputs records each under its name.
  OPAL_MODEL_PARAMETERS(OPAL_VTK_SET_GET)
  ///@}

  /// 0 custom, 1 fig10, 2 fig11, 3 fig12 (default), 4 fig13, 5 fig15, 6 fig17,
  /// 7 harlequin, 8 pinfire. Choosing a preset sets the parameters it stands
  /// for (DomainDiameterRange; harlequin and pinfire also the Voronoi layout's);
  /// a parameter set afterwards is used. Custom sets nothing.
  void SetPreset(int preset);
  vtkGetMacro(Preset, int);
  /// Chooses the preset by name ("fig12", "custom"); false if the name is unknown.
  bool SetPresetByName(const char* name);
  ///@}

  /// Which point arrays port 0 carries (not a model parameter: the opal is
  /// the same): ALL_ARRAYS (0, the default) every array above, or
  /// RENDER_ARRAYS (1) only what the render reads, ScatteringCoefficient,
  /// DomainId, SurfaceDistance and the absorption: 12 bytes per voxel (20
  /// with absorption) instead of 53 (docs/design.md §2.5), for a stone to
  /// be rendered rather than inspected. Another value fails the update, named.
  enum OutputArraysChoice
  {
    ALL_ARRAYS = 0,
    RENDER_ARRAYS = 1,
  };
  vtkSetMacro(OutputArrays, int);
  vtkGetMacro(OutputArrays, int);

  /// The ranks whose Voronoi layouts are built together (docs/design.md
  /// §8.1): each assigns the cells of a share of the grid's layers. The
  /// global controller by default; none, or one process, builds alone. Every
  /// rank's source must update together after a change of its settings, as
  /// ParaView's pvbatch and pvserver update them.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  /// How many ranks assigned the Voronoi cells of the layout the last update
  /// used: the controller's ranks where they shared it, 1 where it was built
  /// alone, 0 for polygons (or none built).
  vtkGetMacro(LastVoronoiCellShares, int);

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
  ~vtkOpalSource() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  OPAL_MODEL_PARAMETERS(OPAL_VTK_MEMBER)
  int Preset;
  int OutputArrays = ALL_ARRAYS;

private:
  vtkOpalSource(const vtkOpalSource&) = delete;
  void operator=(const vtkOpalSource&) = delete;

  // Empty if the parameters are valid and, given an extent to fill, its
  // arrays fit in memory; else the message naming the parameter.
  std::string Validate(const int* extent) const;
  // OutputArrays as the core's choice (of a valid value).
  opal::VolumeArrays arrays() const;
  // Validate's error, said once per change of the settings (the pipeline asks
  // for the information and then the data, ParaView more than once); true if
  // there is one.
  bool Refuses(const int* extent);
  // The domain layout (warning when not all domains fit); nullptr if
  // aborted or `refused` (this rank's request, which still takes part in the
  // ranks' shared build). Built once per change of the model settings and
  // kept: the pieces of one volume (a .pvti written piece by piece) share it.
  std::shared_ptr<const opal::DomainLayout> BuildLayout(const opal::ModelParameters& parameters, bool refused);
  // The layout's polygons (or Voronoi cell boundaries) for port 1, made once per layout.
  vtkPolyData* LayoutPolygons(const opal::ModelParameters& parameters);
  // Fills the image's extent with the voxel arrays; false if aborted.
  bool FillVolume(vtkImageData* image, const opal::ModelParameters& parameters, const opal::DomainLayout& layout);
  // Fills a non-empty extent's fields with the filler; false if aborted.
  bool FillSlabs(const int* extent, const opal::VolumeFiller& filler, const opal::VolumeFields& fields);

  // The error last said and the source's modification time then.
  std::string ReportedError;
  vtkMTimeType ReportedErrorTime = 0;
  // The layout kept, the model settings it was built for, its polygons; the
  // settings of the ranks' last shared build.
  std::shared_ptr<const opal::DomainLayout> Layout;
  std::string LayoutSettings;
  std::string SharedSettings;
  vtkSmartPointer<vtkPolyData> Polygons;
  vtkMultiProcessController* Controller = nullptr;
  int LastVoronoiCellShares = 0;
};
