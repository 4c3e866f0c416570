// Geometry and optics of the paper-scale volume: the filled fraction matches
// the half-ellipsoid, normals are unit vectors where set, diameters lie in
// their ranges, and the per-voxel optics equal the paper's eq. 1-5 computed
// here independently. A spherical cabochon checks SurfaceDistance exactly.
#include "OpalOptics.h"
#include "OpalTestVolumes.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
using opal::Pi;
constexpr double Mu = 1.45;
constexpr double VolumeFraction = 0.2;

// Paper eq. 1 with eq. 2, l and lambda in mm, in 1/mm.
double rayleighEq1(double diameterNm, double volumeFraction, double wavelengthNm)
{
  const double l = diameterNm * 1e-6;
  const double lambda = wavelengthNm * 1e-6;
  const double n = volumeFraction / (Pi * l * l * l / 6.0);
  const double m = 1.55 / 1.33;
  const double k = (m * m - 1.0) / (m * m + 2.0);
  return 2.0 * std::pow(Pi, 5) / 3.0 * n * k * k * std::pow(l, 6) / std::pow(lambda, 4);
}

bool near(double a, double b, double relative)
{
  return std::fabs(a - b) <= relative * std::max(std::fabs(a), std::fabs(b));
}

// The point arrays of the volume that the checks read.
struct VolumeArrays
{
  vtkDataArray* Type;
  vtkDataArray* Diameter;
  vtkDataArray* Normal;
  vtkDataArray* DomainId;
  vtkDataArray* LambdaMax;
  vtkDataArray* LambdaMin;
  vtkDataArray* Scattering;
  vtkDataArray* Distance;
};

VolumeArrays volumeArrays(vtkPointData* pd)
{
  return { pd->GetArray("VoxelType"), pd->GetArray("ParticleDiameter"), pd->GetArray("Normal"),
    pd->GetArray("DomainId"), pd->GetArray("BraggLambdaMax"), pd->GetArray("BraggLambdaMin"),
    pd->GetArray("ScatteringCoefficient"), pd->GetArray("SurfaceDistance") };
}

// Every array of docs/design.md §2.5 exists, with its documented type.
void checkArrayTypes(vtkPointData* pd, const VolumeArrays& a)
{
  for (const char* name : opaltest::volumeArrayNames())
  {
    OPAL_CHECK(pd->GetArray(name) != nullptr, std::string("array ") + name + " exists");
  }
  OPAL_CHECK(std::string(a.Type->GetClassName()) == "vtkUnsignedCharArray", "VoxelType is uint8");
  OPAL_CHECK(std::string(a.DomainId->GetClassName()) == "vtkIntArray", "DomainId is int32");
  OPAL_CHECK(a.Normal->GetNumberOfComponents() == 3, "Normal has 3 components");
  OPAL_CHECK(std::string(a.Diameter->GetClassName()) == "vtkFloatArray", "ParticleDiameter is float");
}

// What the pass over the voxels counts.
struct VoxelTally
{
  long long Filled = 0, BadNormals = 0, BadDiameters = 0, BadOptics = 0, BadSigns = 0;
  long long SurfaceWithoutNormal = 0, ScatteringCount = 0;
  double ScatteringSum = 0;
};

// A voxel with an empty 6-neighbour (or on the grid's edge) is a surface voxel.
bool isSurfaceVoxel(vtkDataArray* type, const int dims[3], vtkIdType id)
{
  const int i = static_cast<int>(id % dims[0]);
  const int j = static_cast<int>((id / dims[0]) % dims[1]);
  const int k = static_cast<int>(id / (static_cast<vtkIdType>(dims[0]) * dims[1]));
  bool surface = i == 0 || j == 0 || k == 0 || i == dims[0] - 1 || j == dims[1] - 1 || k == dims[2] - 1;
  const vtkIdType steps[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  for (int s = 0; s < 3 && !surface; ++s)
  {
    surface = type->GetComponent(id - steps[s], 0) == 0 || type->GetComponent(id + steps[s], 0) == 0;
  }
  return surface;
}

// A body voxel (type 1): Rayleigh scattering of eq. 1-2, no domain, a normal exactly on the surface.
void tallyBodyVoxel(
  const VolumeArrays& a, const int dims[3], vtkIdType id, double l, double length, VoxelTally& tally)
{
  ++tally.ScatteringCount;
  tally.ScatteringSum += a.Scattering->GetComponent(id, 0);
  tally.BadDiameters += !(l >= 5.0 && l <= 50.0);
  tally.BadOptics += !near(a.Scattering->GetComponent(id, 0), rayleighEq1(l, VolumeFraction, 550.0), 1e-5);
  tally.BadOptics += a.DomainId->GetComponent(id, 0) != -1 || a.LambdaMax->GetComponent(id, 0) != 0;
  const bool surface = isSurfaceVoxel(a.Type, dims, id);
  tally.SurfaceWithoutNormal += surface && length == 0;
  tally.BadNormals += !surface && length != 0;
}

// A domain voxel: Bragg wavelengths of eq. 3-5, no scattering, a normal within 30 deg of +y.
void tallyDomainVoxel(const VolumeArrays& a, vtkIdType id, double l, const double n[3], double length,
  VoxelTally& tally)
{
  tally.BadDiameters += !(l >= 250.0 && l <= 350.0);
  const double expectedMax = 2.0 * Mu * std::sqrt(2.0 / 3.0) * l; // eq. 3, 4 at 90 deg
  tally.BadOptics += !near(a.LambdaMax->GetComponent(id, 0), expectedMax, 1e-5);
  tally.BadOptics +=
    !near(a.LambdaMin->GetComponent(id, 0), expectedMax * std::sqrt(1.0 - 1.0 / (Mu * Mu)), 1e-5); // eq. 5
  tally.BadOptics += a.Scattering->GetComponent(id, 0) != 0 || a.DomainId->GetComponent(id, 0) < 0;
  tally.BadNormals += !(length > 0 && n[1] >= 0 && n[1] >= std::cos(30.0 * Pi / 180.0) - 1e-6);
}

void tallyVoxel(const VolumeArrays& a, const int dims[3], vtkIdType id, VoxelTally& tally)
{
  const int t = static_cast<int>(a.Type->GetComponent(id, 0));
  const double l = a.Diameter->GetComponent(id, 0);
  double n[3];
  a.Normal->GetTuple(id, n);
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (length != 0 && std::fabs(length - 1.0) > 1e-5)
  {
    ++tally.BadNormals;
  }
  const double sd = a.Distance->GetComponent(id, 0);
  if ((t != 0 && sd > 1e-6) || (t == 0 && sd < -1e-6))
  {
    ++tally.BadSigns;
  }
  if (t == 0)
  {
    tally.BadDiameters += l != 0;
    tally.BadNormals += length != 0;
    return;
  }
  ++tally.Filled;
  if (t == 1)
  {
    tallyBodyVoxel(a, dims, id, l, length, tally);
  }
  else
  {
    tallyDomainVoxel(a, id, l, n, length, tally);
  }
}

// Every voxel of the default volume: the filled fraction, normals, diameters,
// optics and distance signs, and the mean scattering coefficient.
void checkVoxels(vtkImageData* volume, const VolumeArrays& arrays)
{
  VoxelTally tally;
  const vtkIdType count = volume->GetNumberOfPoints();
  int dims[3];
  volume->GetDimensions(dims);
  for (vtkIdType id = 0; id < count; ++id)
  {
    tallyVoxel(arrays, dims, id, tally);
  }
  const double share = (2.0 / 3.0) * Pi * 8.0 * 8.0 * 10.0 / (16.0 * 8.0 * 20.0);
  const double fraction = static_cast<double>(tally.Filled) / count;
  OPAL_CHECK(std::fabs(fraction - share) <= 0.01 * share,
    "filled fraction " + std::to_string(fraction) + " within 1% of " + std::to_string(share));
  OPAL_CHECK(tally.BadNormals == 0, std::to_string(tally.BadNormals) + " voxels with a wrong normal");
  OPAL_CHECK(tally.SurfaceWithoutNormal == 0,
    std::to_string(tally.SurfaceWithoutNormal) + " surface voxels lack a normal");
  OPAL_CHECK(tally.BadDiameters == 0, std::to_string(tally.BadDiameters) + " diameters outside their range");
  OPAL_CHECK(tally.BadOptics == 0, std::to_string(tally.BadOptics) + " voxels disagree with eq. 1-5");
  OPAL_CHECK(
    tally.BadSigns == 0, std::to_string(tally.BadSigns) + " SurfaceDistance signs disagree with VoxelType");
  const double meanScattering = tally.ScatteringSum / tally.ScatteringCount;
  OPAL_CHECK(meanScattering > 0.3 && meanScattering < 0.4,
    "mean mu_s(550) " + std::to_string(meanScattering) + " /mm is the documented ~0.34");
}

void checkDomainsPlaced(vtkOpalSource* source)
{
  OPAL_CHECK(source->GetOutput()->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0) == 250,
    "all 250 domains placed");
}

// A spherical cabochon of radius 8: the distance is |p| - 8 to the dome or y to the base.
void checkSphereSurfaceDistance()
{
  vtkNew<vtkOpalSource> sphere;
  sphere->SetDimensions(64, 32, 80);
  sphere->SetSemiAxes(8, 8, 8);
  sphere->SetDomainCount(0);
  OPAL_CHECK(sphere->GetExecutive()->Update() == 1, "the spherical volume builds");
  vtkImageData* ball = sphere->GetOutput();
  vtkDataArray* ballDistance = ball->GetPointData()->GetArray("SurfaceDistance");
  double worst = 0;
  for (vtkIdType id = 0; id < ball->GetNumberOfPoints(); ++id)
  {
    double p[3];
    ball->GetPoint(id, p);
    const double radial = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 8.0;
    const double expected = radial <= 0 ? -std::min(-radial, p[1]) : radial;
    worst = std::max(worst, std::fabs(ballDistance->GetComponent(id, 0) - expected));
  }
  OPAL_CHECK(worst < 1e-5, "SurfaceDistance of a sphere exact, worst error " + std::to_string(worst) + " mm");
}
} // namespace

int TestOpalVolumeGeometry(int, char*[])
{
  vtkNew<vtkOpalSource> source; // the defaults: paper scale, preset fig12
  OPAL_CHECK(source->GetExecutive()->Update() == 1, "the default volume builds");
  vtkImageData* volume = source->GetOutput();
  const VolumeArrays arrays = volumeArrays(volume->GetPointData());
  checkArrayTypes(volume->GetPointData(), arrays);
  checkVoxels(volume, arrays);
  checkDomainsPlaced(source);
  checkSphereSurfaceDistance();
  return opaltest::finish("TestOpalVolumeGeometry");
}
