// Absorption, the backing layer and scattering inside domains
// (docs/design.md §2.10, §3.9) through the VTK layer: the paper's volume has
// no absorption arrays and records the new settings as 0; with them on, each
// voxel's AbsorptionCoefficient and AbsorptionExponent are the body's above
// BackingThickness and the backing's (grey) below, the domains scatter
// DomainScatteringCoefficient, pieces equal the whole; the render reads the
// arrays and the backing darkens the body.
#include "OpalTestHarness.h"
#include "OpalTestVolumes.h"
#include "OpalRenderScenes.h"
#include "vtkOpalSpectralRender.h"

#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace
{
constexpr double Body = 0.2, Exponent = 3.0, Backing = 1.6, BackingAbsorption = 4.0, DomainScattering = 0.7;

vtkSmartPointer<vtkOpalSource> makeAbsorbingSource()
{
  auto source = opaltest::makeSmallSource();
  source->SetBodyAbsorption(Body);
  source->SetBodyAbsorptionExponent(Exponent);
  source->SetBackingThickness(Backing);
  source->SetBackingAbsorption(BackingAbsorption);
  source->SetDomainScatteringCoefficient(DomainScattering);
  return source;
}

// The paper's volume: no absorption arrays, the settings recorded as 0.
void checkPaperVolume()
{
  auto source = opaltest::makeSmallSource();
  source->Update();
  vtkImageData* volume = source->GetOutput();
  OPAL_CHECK(!volume->GetPointData()->GetArray("AbsorptionCoefficient") &&
      !volume->GetPointData()->GetArray("AbsorptionExponent"),
    "without absorption the volume has no absorption arrays");
  for (const char* name :
    { "BodyAbsorption", "BodyAbsorptionExponent", "BackingThickness", "BackingAbsorption", "DomainScatteringCoefficient" })
  {
    vtkDataArray* recorded = volume->GetFieldData()->GetArray(name);
    OPAL_CHECK(recorded && recorded->GetComponent(0, 0) == 0, std::string("field data records ") + name + " = 0");
  }
}

// Every voxel's absorption and the domains' scattering, by region.
void checkAbsorbingVolume()
{
  auto source = makeAbsorbingSource();
  source->Update();
  vtkImageData* volume = source->GetOutput();
  vtkPointData* points = volume->GetPointData();
  vtkDataArray* absorption = points->GetArray("AbsorptionCoefficient");
  vtkDataArray* exponent = points->GetArray("AbsorptionExponent");
  vtkDataArray* type = points->GetArray("VoxelType");
  vtkDataArray* scattering = points->GetArray("ScatteringCoefficient");
  OPAL_CHECK(absorption && exponent, "with absorption the volume carries AbsorptionCoefficient and AbsorptionExponent");
  if (!absorption || !exponent)
  {
    return;
  }
  long long wrong = 0, backingVoxels = 0, domainVoxels = 0;
  for (vtkIdType i = 0; i < volume->GetNumberOfPoints(); ++i)
  {
    const int voxelType = static_cast<int>(type->GetComponent(i, 0));
    const bool inBacking = voxelType != 0 && volume->GetPoint(i)[1] < Backing;
    const double mua = voxelType == 0 ? 0.0 : (inBacking ? BackingAbsorption : Body);
    const double p = voxelType == 0 || inBacking ? 0.0 : Exponent;
    wrong += absorption->GetComponent(i, 0) != static_cast<float>(mua) || exponent->GetComponent(i, 0) != p;
    wrong += voxelType == 2 && scattering->GetComponent(i, 0) != static_cast<float>(DomainScattering);
    backingVoxels += inBacking;
    domainVoxels += voxelType == 2;
  }
  OPAL_CHECK(wrong == 0 && backingVoxels > 0 && domainVoxels > 0,
    std::to_string(wrong) + " voxels with the wrong absorption or domain scattering (" + std::to_string(backingVoxels) +
      " in the backing, " + std::to_string(domainVoxels) + " in domains)");
  OPAL_CHECK(volume->GetFieldData()->GetArray("BackingThickness")->GetComponent(0, 0) == Backing,
    "field data records BackingThickness");
}

// A piece of the absorbing volume equals the whole's values.
void checkPieces()
{
  auto whole = makeAbsorbingSource();
  whole->Update();
  auto piece = makeAbsorbingSource();
  piece->UpdatePiece(1, 3, 0);
  for (const char* name : { "AbsorptionCoefficient", "AbsorptionExponent", "ScatteringCoefficient" })
  {
    OPAL_CHECK(opaltest::countDifferences(whole->GetOutput(), piece->GetOutput(), name) == 0,
      std::string("piece 1 of 3 equals the whole in ") + name);
  }
}

// Mean luminance Y of the stone's pixels, rendered from the volume's arrays
// at a fixed exposure.
double meanLuminance(vtkOpalSource* source, const std::string& what)
{
  vtkNew<vtkOpalSpectralRender> render;
  render->SetInputConnection(source->GetOutputPort(0));
  render->SetImageSize(48, 36);
  render->SetExposure(1.0);
  OPAL_CHECK(render->GetExecutive()->Update() == 1, what + ": the render runs");
  OPAL_CHECK(render->GetNumberOfValidationMessages() == 0, what + ": the validation layer is silent");
  vtkDataArray* xyz = render->GetOutput()->GetPointData()->GetArray("XYZ");
  vtkDataArray* depth = render->GetOutput()->GetPointData()->GetArray("Depth");
  double sum = 0;
  long long hit = 0;
  for (vtkIdType i = 0; xyz && i < xyz->GetNumberOfTuples(); ++i)
  {
    if (depth->GetComponent(i, 0) > 0)
    {
      sum += xyz->GetComponent(i, 1);
      ++hit;
    }
  }
  return hit > 0 ? sum / static_cast<double>(hit) : 0.0;
}

// The backing (a third of the stone's height, opaque) darkens the body seen
// from above: what the light would have scattered back from below it is gone.
void checkBackingDarkens()
{
  auto plain = opaltest::makeSmallSource();
  auto backed = opaltest::makeSmallSource();
  backed->SetBackingThickness(3.0);
  backed->SetBackingAbsorption(20.0);
  const double without = meanLuminance(plain, "no backing"), with = meanLuminance(backed, "backing");
  std::cout << "mean luminance of the stone: " << without << " without a backing, " << with << " with" << std::endl;
  OPAL_CHECK(with > 0 && with < 0.95 * without, "the backing darkens the stone by more than 5%: " +
      std::to_string(with) + " against " + std::to_string(without));
}

// An absorbing volume of the render's arrays only (OutputArrays render: the
// absorption's two arrays kept) renders the whole set's image exactly.
void checkRenderArraysOnly()
{
  auto all = makeAbsorbingSource();
  auto renderOnly = makeAbsorbingSource();
  renderOnly->SetOutputArrays(vtkOpalSource::RENDER_ARRAYS);
  renderOnly->Update();
  OPAL_CHECK(renderOnly->GetOutput()->GetPointData()->GetNumberOfArrays() == 5 &&
      renderOnly->GetOutput()->GetPointData()->GetArray("AbsorptionExponent"),
    "the render's arrays of an absorbing volume: five, the absorption's included");
  vtkNew<vtkOpalSpectralRender> a, b;
  a->SetInputConnection(all->GetOutputPort(0));
  b->SetInputConnection(renderOnly->GetOutputPort(0));
  for (vtkOpalSpectralRender* render : { a.Get(), b.Get() })
  {
    render->SetImageSize(48, 36);
    OPAL_CHECK(render->GetExecutive()->Update() == 1, "an absorbing volume of either set renders");
  }
  for (const char* name : { "RGB", "XYZ", "Radiance" })
  {
    OPAL_CHECK(opaltest::countDifferences(a->GetOutput(), b->GetOutput(), name) == 0,
      std::string("the render's arrays alone give the whole set's ") + name);
  }
}
} // namespace

int TestOpalAbsorption(int, char*[])
{
  checkPaperVolume();
  checkAbsorbingVolume();
  checkPieces();
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  checkBackingDarkens();
  checkRenderArraysOnly();
  return opaltest::finish("TestOpalAbsorption");
}
