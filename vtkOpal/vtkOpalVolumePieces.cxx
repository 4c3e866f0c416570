#include "vtkOpalVolumePieces.h"

#include "vtkDataArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace vtkOpalVolumePieces
{
namespace
{
// The point arrays the render reads (vtkOpalRenderInput).
constexpr std::array<const char*, 5> RenderArrays = { "ScatteringCoefficient", "DomainId", "SurfaceDistance",
  "AbsorptionCoefficient", "AbsorptionExponent" };

vtkMultiProcessController* ranksController(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

vtkIdType pointsIn(const int* e)
{
  vtkIdType points = 1;
  for (int a = 0; a < 3; ++a)
  {
    points *= std::max(e[2 * a + 1] - e[2 * a] + 1, 0);
  }
  return points;
}

// Copies each rank's rows of one array (`bytes`, the ranks' pieces one after
// another) into `whole` at their extents.
void placeRows(const std::vector<char>& bytes, const std::vector<int>& extents, const int* w, vtkDataArray* whole)
{
  const vtkIdType tupleBytes = whole->GetNumberOfComponents() * whole->GetDataTypeSize();
  char* target = static_cast<char*>(whole->GetVoidPointer(0));
  const vtkIdType nx = w[1] - w[0] + 1, ny = w[3] - w[2] + 1;
  std::size_t at = 0;
  for (std::size_t r = 0; r < extents.size() / 6; ++r)
  {
    const int* e = &extents[6 * r];
    const vtkIdType row = std::max(e[1] - e[0] + 1, 0) * tupleBytes;
    for (int k = e[4]; k <= e[5] && row > 0; ++k)
    {
      for (int j = e[2]; j <= e[3]; ++j, at += row)
      {
        std::memcpy(target + (((k - w[4]) * ny + (j - w[2])) * nx + (e[0] - w[0])) * tupleBytes, &bytes[at], row);
      }
    }
  }
}

// Every rank's values of one array, the ranks' pieces one after another.
std::vector<char> gatherBytes(vtkMultiProcessController* controller, vtkDataArray* mine)
{
  const int ranks = controller->GetNumberOfProcesses();
  const vtkIdType length = mine->GetNumberOfValues() * mine->GetDataTypeSize();
  std::vector<vtkIdType> lengths(ranks), offsets(ranks);
  controller->AllGather(&length, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[r] = total;
    total += lengths[r];
  }
  std::vector<char> bytes(static_cast<std::size_t>(total));
  controller->AllGatherV(static_cast<const char*>(mine->GetVoidPointer(0)), bytes.data(), length, lengths.data(),
    offsets.data());
  return bytes;
}
} // namespace

void PieceExtent(vtkMultiProcessController* given, const int whole[6], int extent[6])
{
  vtkMultiProcessController* controller = ranksController(given);
  std::copy(whole, whole + 6, extent);
  if (controller && pointsIn(whole) > 0)
  {
    vtkNew<vtkExtentTranslator> translator;
    translator->PieceToExtentThreadSafe(controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), 0,
      const_cast<int*>(whole), extent, vtkExtentTranslator::BLOCK_MODE, 0);
  }
}

std::string Gather(
  vtkMultiProcessController* given, vtkImageData* piece, const int whole[6], vtkSmartPointer<vtkImageData>& volume)
{
  volume = vtkSmartPointer<vtkImageData>::New();
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    volume->ShallowCopy(piece);
    return {};
  }
  const int ranks = controller->GetNumberOfProcesses();
  std::vector<int> extents(6 * ranks);
  controller->AllGather(piece->GetExtent(), extents.data(), 6);
  volume->SetExtent(const_cast<int*>(whole));
  volume->SetOrigin(piece->GetOrigin());
  volume->SetSpacing(piece->GetSpacing());
  volume->GetFieldData()->ShallowCopy(piece->GetFieldData());
  const bool empty = pointsIn(piece->GetExtent()) == 0;
  for (const char* name : RenderArrays)
  {
    // Each array's type and components (0: absent), agreed over the ranks
    // whose piece holds points (-1: an empty piece takes the others').
    vtkDataArray* mine = piece->GetPointData()->GetArray(name);
    const int kind = empty ? -1 : mine && mine->HasStandardMemoryLayout() ? mine->GetDataType() * 8 + mine->GetNumberOfComponents() : 0;
    std::vector<int> kinds(ranks);
    controller->AllGather(&kind, kinds.data(), 1);
    kinds.erase(std::remove(kinds.begin(), kinds.end(), -1), kinds.end());
    if (std::any_of(kinds.begin(), kinds.end(), [&](int k) { return k != kinds.front(); }))
    {
      return std::string("The ranks' pieces of the volume differ in the point array ") + name +
        " (present, type or components): every rank must read the same volume.";
    }
    if (kinds.empty() || kinds.front() == 0)
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> array = vtkSmartPointer<vtkDataArray>::Take(
      vtkDataArray::CreateDataArray(kinds.front() / 8));
    array->SetNumberOfComponents(kinds.front() % 8);
    vtkSmartPointer<vtkDataArray> sent = mine ? vtkSmartPointer<vtkDataArray>(mine) : array;
    const std::vector<char> bytes = gatherBytes(controller, sent);
    array->SetName(name);
    array->SetNumberOfTuples(pointsIn(whole));
    placeRows(bytes, extents, whole, array);
    volume->GetPointData()->AddArray(array);
  }
  return {};
}
} // namespace vtkOpalVolumePieces
