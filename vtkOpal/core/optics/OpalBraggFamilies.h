// The Bragg map in the coupled-wave model (docs/design.md §7.3): for a domain
// and a light, each reflecting plane family's Bragg wavelength and the peak
// reflectance of its coherent layers there, as the render's coupled-wave
// model sees them (§7.2), so the map shows which families of which domains
// can flash for that light, and how strongly.
#pragma once

#include "OpalCoupledWave.h"
#include "OpalRenderParameters.h"

#include <array>
#include <vector>

namespace opal
{

struct BraggFamilySettings
{
  LatticePlaneSet LatticePlanes = LatticePlaneSet::Stacking111; // (111) only, or all 13 families
  int CoherentLayers = 200;  // N: the map knows no crossing, so the coherent depth bounds it
  ColloidalCrystal Crystal;  // sphere and matrix indices; n_bar sets lambda_B in this model
};

// One family for the light: lambda_B = 2 d n_bar sin theta2 (order 1, nm; 0
// at grazing light) and the reflectance of CoherentLayers layers at lambda_B,
// s and p averaged (tanh^2 of the coupling times the thickness, below 1).
struct BraggFamilyValue
{
  double Wavelength = 0.0;
  double PeakReflectance = 0.0;
};

// The families (1 or 13, OpalLatticePlanes' order: (111) first) of a domain
// of sphere diameter D whose lattice orientation is the unit quaternion
// (w, x, y, z) (the volume's LatticeOrientation), at a point, for the
// direction `towardLight` (unit, in the stone's frame).
std::vector<BraggFamilyValue> braggFamiliesAt(const std::array<double, 4>& orientation, double diameterNm,
  const std::array<double, 3>& towardLight, const BraggFamilySettings& settings);

} // namespace opal
