// libFuzzer target: crafted image data, as a hand-made or damaged .vti would
// bring it, through the readers of the render (vtkOpalRenderInput::Read, then
// the values' rules, validate(RenderVolume)) and the Bragg map (the paper's
// model, coupled-wave with the (111) family and with every fcc family).
// Every input is either refused with a message or read and mapped without a
// crash, an overrun (AddressSanitizer) or a non-finite output.
//
// The bytes (what the seed corpus in corpus/image-data holds):
//   3 bytes   the grid's points along x, y, z (each 1 + byte % 6)
//   then records, one per array, while bytes remain:
//     byte    the name (an index into arrayNames)
//     byte    bit 0: field data instead of point data; bits 1-3: the type
//             (float, double, int, long long, unsigned char, text)
//     byte    components, 1 + byte % 70
//     byte    tuples: 255 for one per point, else the byte itself
//     byte    n, then n bytes of values, each an index into valuePalette,
//             repeated to fill the array (n = 0: every value 1)
#include "OpalRenderVolume.h"
#include "vtkOpalBraggMap.h"
#include "vtkOpalRenderInput.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLongLongArray.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace
{
const std::array<const char*, 16> arrayNames = { "ScatteringCoefficient", "DomainId", "SurfaceDistance",
  "AbsorptionCoefficient", "AbsorptionExponent", "Normal", "ParticleDiameter", "LatticeOrientation", "DomainNormal",
  "DomainParticleDiameter", "DomainOrientation", "SphereRefractiveIndex", "MatrixRefractiveIndex", "RefractiveIndex",
  "Preset", "VoxelType" };

// Values that sit on the rules' edges: ids that wrap int32, indices below 1,
// non-finite numbers, the opal's own magnitudes.
const std::array<double, 16> valuePalette = { 0.0, 1.0, -1.0, 0.5, 1.45, 2.0, 3.0, 250.0, -2.0, 1e9, 4294967296.0,
  1e300, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1.5, 0.1 };

class ByteReader
{
public:
  ByteReader(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  bool more() const { return this->Offset < this->Size; }
  std::uint8_t byte() { return this->Offset < this->Size ? this->Data[this->Offset++] : 0; }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Offset = 0;
};

vtkSmartPointer<vtkAbstractArray> arrayOfType(int type)
{
  switch (type % 6)
  {
    case 0: return vtkSmartPointer<vtkFloatArray>::New();
    case 1: return vtkSmartPointer<vtkDoubleArray>::New();
    case 2: return vtkSmartPointer<vtkIntArray>::New();
    case 3: return vtkSmartPointer<vtkLongLongArray>::New();
    case 4: return vtkSmartPointer<vtkUnsignedCharArray>::New();
    default: return vtkSmartPointer<vtkStringArray>::New();
  }
}

// One array record of the bytes, added to the image.
void addArray(ByteReader& bytes, vtkImageData* image)
{
  const char* name = arrayNames[bytes.byte() % arrayNames.size()];
  const std::uint8_t kind = bytes.byte();
  vtkSmartPointer<vtkAbstractArray> array = arrayOfType(kind >> 1);
  array->SetName(name);
  array->SetNumberOfComponents(1 + bytes.byte() % 70);
  const std::uint8_t tuples = bytes.byte();
  array->SetNumberOfTuples(tuples == 255 ? image->GetNumberOfPoints() : tuples);
  std::array<double, 255> values{};
  const std::size_t count = bytes.byte();
  for (std::size_t i = 0; i < count; ++i)
  {
    values[i] = valuePalette[bytes.byte() % valuePalette.size()];
  }
  auto* numbers = vtkDataArray::SafeDownCast(array);
  for (vtkIdType i = 0; numbers && i < numbers->GetNumberOfValues(); ++i)
  {
    numbers->SetVariantValue(i, count ? values[static_cast<std::size_t>(i) % count] : 1.0);
  }
  (kind & 1 ? image->GetFieldData() : static_cast<vtkFieldData*>(image->GetPointData()))->AddArray(array);
}

// The render's reading of the image: refused, or read and valid, never a crash.
void readForRender(vtkImageData* image)
{
  opal::RenderVolume volume;
  vtkOpalRenderInput::Storage storage;
  if (vtkOpalRenderInput::Read(image, volume, storage).empty())
  {
    (void)opal::validate(volume);
  }
}

// Aborts (a finding) when the Bragg map produced a non-finite output from
// arrays the rule let through: the rule has a gap.
class NonFiniteOutput : public vtkCommand
{
public:
  static NonFiniteOutput* New() { return new NonFiniteOutput; }
  void Execute(vtkObject*, unsigned long, void* message) override
  {
    if (message && std::strstr(static_cast<const char*>(message), "produced a NaN"))
    {
      std::fprintf(stderr, "%s\n", static_cast<const char*>(message));
      std::abort();
    }
  }
};

// The Bragg map of each model and lattice setting: refused with a message or
// every output finite.
void mapEverySetting(vtkImageData* image)
{
  vtkNew<NonFiniteOutput> finding;
  for (const auto& [model, planes] : { std::pair<int, int>{ 0, 0 }, { 1, 0 }, { 1, 1 } })
  {
    vtkNew<vtkOpalBraggMap> map;
    map->SetBraggModel(model);
    map->SetLatticePlanes(planes);
    map->SetCoherentLayers(20);
    map->AddObserver(vtkCommand::ErrorEvent, finding);
    map->SetInputData(image);
    map->GetExecutive()->Update();
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); // refusals are expected
  ByteReader bytes(data, size);
  vtkNew<vtkImageData> image;
  image->SetDimensions(1 + bytes.byte() % 6, 1 + bytes.byte() % 6, 1 + bytes.byte() % 6);
  image->SetSpacing(4, 4, 4);
  image->SetOrigin(-10, -2, -10);
  for (int records = 0; bytes.more() && records < 24; ++records)
  {
    addArray(bytes, image);
  }
  readForRender(image);
  mapEverySetting(image);
  return 0;
}
