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

#include <cmath>
#include <string>

namespace
{
using opal::Pi;

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
} // namespace

int main()
{
  using opaltest::check;
  vtkNew<vtkOpalSource> source; // the defaults: paper scale, preset fig12
  OPAL_CHECK(source->GetExecutive()->Update() == 1, "the default volume builds");
  vtkImageData* volume = source->GetOutput();
  vtkPointData* pd = volume->GetPointData();
  vtkDataArray* type = pd->GetArray("VoxelType");
  vtkDataArray* diameter = pd->GetArray("ParticleDiameter");
  vtkDataArray* normal = pd->GetArray("Normal");
  vtkDataArray* domainId = pd->GetArray("DomainId");
  vtkDataArray* lambdaMax = pd->GetArray("BraggLambdaMax");
  vtkDataArray* lambdaMin = pd->GetArray("BraggLambdaMin");
  vtkDataArray* scattering = pd->GetArray("ScatteringCoefficient");
  vtkDataArray* distance = pd->GetArray("SurfaceDistance");
  for (const char* name : opaltest::volumeArrayNames())
  {
    OPAL_CHECK(pd->GetArray(name) != nullptr, std::string("array ") + name + " exists");
  }
  OPAL_CHECK(std::string(type->GetClassName()) == "vtkUnsignedCharArray", "VoxelType is uint8");
  OPAL_CHECK(std::string(domainId->GetClassName()) == "vtkIntArray", "DomainId is int32");
  OPAL_CHECK(normal->GetNumberOfComponents() == 3, "Normal has 3 components");
  OPAL_CHECK(std::string(diameter->GetClassName()) == "vtkFloatArray", "ParticleDiameter is float");

  const double mu = 1.45;
  const double volumeFraction = 0.2;
  long long filled = 0, badNormals = 0, badDiameters = 0, badOptics = 0, badSigns = 0;
  long long surfaceWithoutNormal = 0, scatteringCount = 0;
  double scatteringSum = 0;
  const vtkIdType count = volume->GetNumberOfPoints();
  int dims[3];
  volume->GetDimensions(dims);
  for (vtkIdType id = 0; id < count; ++id)
  {
    const int t = static_cast<int>(type->GetComponent(id, 0));
    const double l = diameter->GetComponent(id, 0);
    double n[3];
    normal->GetTuple(id, n);
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (length != 0 && std::fabs(length - 1.0) > 1e-5)
    {
      ++badNormals;
    }
    const double sd = distance->GetComponent(id, 0);
    if ((t != 0 && sd > 1e-6) || (t == 0 && sd < -1e-6))
    {
      ++badSigns;
    }
    if (t == 0)
    {
      badDiameters += l != 0;
      badNormals += length != 0;
      continue;
    }
    ++filled;
    if (t == 1)
    {
      ++scatteringCount;
      scatteringSum += scattering->GetComponent(id, 0);
      badDiameters += !(l >= 5.0 && l <= 50.0);
      badOptics += !near(scattering->GetComponent(id, 0), rayleighEq1(l, volumeFraction, 550.0), 1e-5);
      badOptics += domainId->GetComponent(id, 0) != -1 || lambdaMax->GetComponent(id, 0) != 0;
      // A voxel with an empty 6-neighbour (or on the grid's edge) is a surface voxel.
      const int i = static_cast<int>(id % dims[0]);
      const int j = static_cast<int>((id / dims[0]) % dims[1]);
      const int k = static_cast<int>(id / (static_cast<vtkIdType>(dims[0]) * dims[1]));
      bool surface = i == 0 || j == 0 || k == 0 || i == dims[0] - 1 || j == dims[1] - 1 || k == dims[2] - 1;
      const vtkIdType steps[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
      for (int s = 0; s < 3 && !surface; ++s)
      {
        surface = type->GetComponent(id - steps[s], 0) == 0 || type->GetComponent(id + steps[s], 0) == 0;
      }
      surfaceWithoutNormal += surface && length == 0;
      badNormals += !surface && length != 0;
    }
    else
    {
      badDiameters += !(l >= 250.0 && l <= 350.0);
      const double expectedMax = 2.0 * mu * std::sqrt(2.0 / 3.0) * l; // eq. 3, 4 at 90 deg
      badOptics += !near(lambdaMax->GetComponent(id, 0), expectedMax, 1e-5);
      badOptics +=
        !near(lambdaMin->GetComponent(id, 0), expectedMax * std::sqrt(1.0 - 1.0 / (mu * mu)), 1e-5); // eq. 5
      badOptics += scattering->GetComponent(id, 0) != 0 || domainId->GetComponent(id, 0) < 0;
      badNormals += !(length > 0 && n[1] >= 0 && n[1] >= std::cos(30.0 * Pi / 180.0) - 1e-6);
    }
  }
  const double share = (2.0 / 3.0) * Pi * 8.0 * 8.0 * 10.0 / (16.0 * 8.0 * 20.0);
  const double fraction = static_cast<double>(filled) / count;
  OPAL_CHECK(std::fabs(fraction - share) <= 0.01 * share,
    "filled fraction " + std::to_string(fraction) + " within 1% of " + std::to_string(share));
  OPAL_CHECK(badNormals == 0, std::to_string(badNormals) + " voxels with a wrong normal");
  OPAL_CHECK(surfaceWithoutNormal == 0, std::to_string(surfaceWithoutNormal) + " surface voxels lack a normal");
  OPAL_CHECK(badDiameters == 0, std::to_string(badDiameters) + " diameters outside their range");
  OPAL_CHECK(badOptics == 0, std::to_string(badOptics) + " voxels disagree with eq. 1-5");
  OPAL_CHECK(badSigns == 0, std::to_string(badSigns) + " SurfaceDistance signs disagree with VoxelType");
  const double meanScattering = scatteringSum / scatteringCount;
  OPAL_CHECK(meanScattering > 0.3 && meanScattering < 0.4,
    "mean mu_s(550) " + std::to_string(meanScattering) + " /mm is the documented ~0.34");
  OPAL_CHECK(source->GetOutput()->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0) == 250,
    "all 250 domains placed");

  // A spherical cabochon of radius 8: the distance is |p| - 8 to the dome or y to the base.
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
  return opaltest::finish("TestOpalVolumeGeometry");
}
