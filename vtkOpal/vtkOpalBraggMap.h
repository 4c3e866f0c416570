/**
 * @class vtkOpalBraggMap
 * @brief The Bragg-Snell wavelength each opal domain diffracts for a light.
 *
 * Input: the opal volume (point arrays) or the domain polygons (cell arrays)
 * of vtkOpalSource, with DomainId, Normal and ParticleDiameter. Adds, on the
 * same association, BraggWavelength (nm: lambda_B = 2 d sqrt(mu^2 - cos^2
 * theta1) / k, theta1 the glancing angle of the light on the lattice planes,
 * d = sqrt(2/3) l), BraggVisible (1 where lambda_B lies in the visible range,
 * times the mosaic weight towards the eye when MosaicSpread > 0; else 0) and
 * BraggColor (uint8 x 3, the sRGB colour of lambda_B). Outside domains all
 * three are 0.
 *
 * With BraggModel coupled-wave (docs/design.md §7.3) lambda_B is the
 * coupled-wave model's, 2 d n_bar sin theta2 / k with n_bar from the volume's
 * SphereRefractiveIndex and MatrixRefractiveIndex, and BraggPeakReflectance
 * is the (111) family's reflectance of CoherentLayers layers at its lambda_B;
 * with LatticePlanes fcc also FamilyBraggWavelength and FamilyPeakReflectance
 * (13 components, the families in OpalLatticePlanes' order), which need the
 * volume's LatticeOrientation.
 */
#pragma once

#include "vtkOpalModule.h" // for export macro
#include "vtkPassInputTypeAlgorithm.h"

#include <string> // for SettingsError

namespace opal
{
struct BraggMapSettings;
}


class VTKOPAL_EXPORT vtkOpalBraggMap : public vtkPassInputTypeAlgorithm
{
public:
  static vtkOpalBraggMap* New();
  vtkTypeMacro(vtkOpalBraggMap, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Light position in mm. Default (0, 60, 0), the paper's.
  vtkSetVector3Macro(LightPosition, double);
  vtkGetVector3Macro(LightPosition, double);
  /// Eye position in mm, for the mosaic weight. Default (0, 60, 0).
  vtkSetVector3Macro(EyePosition, double);
  vtkGetVector3Macro(EyePosition, double);
  /// The stone's turn in degrees about x, then y, then z, under the fixed light
  /// and eye — the render's ModelRotation, so both can share one light and eye.
  /// Default (0, 0, 0).
  vtkSetVector3Macro(ModelRotation, double);
  vtkGetVector3Macro(ModelRotation, double);
  /// Refractive index mu; 0 (the default): the input volume's (field data RefractiveIndex).
  vtkSetMacro(RefractiveIndex, double);
  vtkGetMacro(RefractiveIndex, double);
  /// Bragg order k. Default 1.
  vtkSetMacro(BraggOrder, int);
  vtkGetMacro(BraggOrder, int);
  /// Angular spread in degrees of the mosaic weight; 0 = off (the paper).
  vtkSetMacro(MosaicSpread, double);
  vtkGetMacro(MosaicSpread, double);
  /// 0: the paper's Bragg-Snell wavelength; 1: the coupled-wave model's, with
  /// the peak reflectance. Default 0, as the render's BraggModel.
  vtkSetMacro(BraggModel, int);
  vtkGetMacro(BraggModel, int);
  /// 0: the (111) planes; 1: all 13 FCC families (needs BraggModel 1). Default 0.
  vtkSetMacro(LatticePlanes, int);
  vtkGetMacro(LatticePlanes, int);
  /// The lattice layers that reflect coherently, N of the peak reflectance. Default 200.
  vtkSetMacro(CoherentLayers, int);
  vtkGetMacro(CoherentLayers, int);

protected:
  vtkOpalBraggMap();
  ~vtkOpalBraggMap() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double LightPosition[3];
  double EyePosition[3];
  double ModelRotation[3];
  double RefractiveIndex;
  int BraggOrder;
  double MosaicSpread;
  int BraggModel;
  int LatticePlanes;
  int CoherentLayers;

private:
  opal::BraggMapSettings GetSettings() const;
  // Empty, or a sentence naming the property that is out of range.
  std::string SettingsError() const;

  vtkOpalBraggMap(const vtkOpalBraggMap&) = delete;
  void operator=(const vtkOpalBraggMap&) = delete;
};
