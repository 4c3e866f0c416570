// The gather of the volume's pieces under MPI (vtkOpalVolumePieces, docs/design.md
// §8.1), run with mpiexec on 3 ranks, in exchange rounds of a few bytes, so
// that rounds end within a row and within a value: each round is placed as it
// arrives (the product's 64 MiB rounds are never filled by the test volumes,
// so only here do they end mid-row). Each rank builds its piece of an absorbing
// opal; gathered whole (one share) and by layers (each rank's share of a
// shared march: SurfaceDistance whole, the medium's arrays for the layers its
// device reads), every array equals, value for value, the same extent of the
// volume one process builds whole.
#include "OpalRankVerdict.h"
#include "vtkOpalRenderInput.h"
#include "vtkOpalSource.h"
#include "vtkOpalVolumePieces.h"

#include "vtkDataArray.h"
#include "vtkExtentTranslator.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <iostream>
#include <string>

namespace
{
constexpr int Dimensions[3] = { 11, 7, 13 }; // a row of 11 values: 44 or 88 bytes

vtkSmartPointer<vtkOpalSource> absorbingOpal()
{
  auto source = vtkSmartPointer<vtkOpalSource>::New();
  source->SetController(nullptr); // each builds alone; the gather is what is tested
  source->SetDimensions(Dimensions[0], Dimensions[1], Dimensions[2]);
  source->SetDomainCount(6);
  source->SetBodyAbsorption(0.2);
  source->SetBodyAbsorptionExponent(1.5);
  return source;
}

// The layers z [first, end) of the medium a share of a shared march reads
// (opal::mediumLayersRead): its share of the layers and 7 beside it (the
// 6 its device holds, the cells and SurfaceDistance, and the skin's one).
std::pair<int, int> layersRead(int share, int shares)
{
  const int nz = Dimensions[2];
  return { std::max(0, share * nz / shares - 7), std::min(nz, (share + 1) * nz / shares + 7) };
}

// Whether `array` of `image` holds at each of its points the values of the
// same point of `whole` (an image of the whole extent).
bool sameValues(vtkImageData* image, vtkImageData* whole, const char* name, int rank, const std::string& what)
{
  vtkDataArray* array = image->GetPointData()->GetArray(name);
  vtkDataArray* expected = whole->GetPointData()->GetArray(name);
  const int* e = image->GetExtent();
  for (int k = e[4]; array && expected && k <= e[5]; ++k)
  {
    for (int j = e[2]; j <= e[3]; ++j)
    {
      for (int i = e[0]; i <= e[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        const vtkIdType at = image->ComputePointId(ijk), from = whole->ComputePointId(ijk);
        for (int c = 0; c < expected->GetNumberOfComponents(); ++c)
        {
          if (array->GetComponent(at, c) != expected->GetComponent(from, c))
          {
            std::cerr << "rank " << rank << ", " << what << ": " << name << " at (" << i << ", " << j << ", " << k
                      << ") is " << array->GetComponent(at, c) << ", not " << expected->GetComponent(from, c) << std::endl;
            return false;
          }
        }
      }
    }
  }
  if (!array || !expected)
  {
    std::cerr << "rank " << rank << ", " << what << ": no " << name << std::endl;
  }
  return array && expected;
}

// Gathers `piece` in rounds of `roundBytes` for `heldPiece` and compares with `whole`.
bool checkGather(vtkMPIController* controller, vtkOpalSource* piece, vtkImageData* whole,
  std::pair<int, int> heldPiece, vtkIdType roundBytes)
{
  const int rank = controller->GetLocalProcessId();
  const std::string what = "rounds of " + std::to_string(roundBytes) + " bytes, share " +
    std::to_string(heldPiece.first) + " of " + std::to_string(heldPiece.second);
  vtkOpalVolumePieces::GatheredVolume gathered;
  gathered.SetRoundBytes(roundBytes);
  vtkImageData* mine = piece->GetOutput();
  const std::string error = gathered.Update(controller, mine, piece->GetOutputInformation(0), true, heldPiece);
  vtkImageData* volume = gathered.Of(controller, mine);
  if (!error.empty() || !volume)
  {
    std::cerr << "rank " << rank << ", " << what << ": " << (error.empty() ? "no volume" : error) << std::endl;
    return false;
  }
  bool passed = sameValues(volume, whole, "SurfaceDistance", rank, what);
  const vtkOpalRenderInput::MediumPiece* medium = gathered.Medium();
  vtkImageData* mediumImage = medium ? medium->Arrays.Get() : volume;
  const std::pair<int, int> layers = layersRead(heldPiece.first, heldPiece.second);
  const int* e = mediumImage->GetExtent();
  if (heldPiece.second > 1 && (!medium || medium->Held.Layers != layers || e[4] != layers.first || e[5] != layers.second - 1))
  {
    std::cerr << "rank " << rank << ", " << what << ": the medium's layers are not those its device reads" << std::endl;
    passed = false;
  }
  for (const char* name : { "ScatteringCoefficient", "DomainId", "AbsorptionCoefficient", "AbsorptionExponent" })
  {
    passed = sameValues(mediumImage, whole, name, rank, what) && passed;
  }
  return passed;
}
} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  const int rank = controller->GetLocalProcessId(), ranks = controller->GetNumberOfProcesses();
  vtkSmartPointer<vtkOpalSource> whole = absorbingOpal();
  whole->Update();
  // This rank's piece, as the render asks for it (AskForPiece's extent).
  vtkSmartPointer<vtkOpalSource> piece = absorbingOpal();
  piece->UpdateInformation();
  int extent[6];
  vtkNew<vtkExtentTranslator> translator;
  int wholeExtent[6] = { 0, Dimensions[0] - 1, 0, Dimensions[1] - 1, 0, Dimensions[2] - 1 };
  translator->PieceToExtentThreadSafe(rank, ranks, 0, wholeExtent, extent, vtkExtentTranslator::BLOCK_MODE, 0);
  piece->UpdateExtent(extent);
  bool passed = true;
  for (const vtkIdType roundBytes : { vtkIdType(7), vtkIdType(44), vtkIdType(1000), vtkIdType(64) << 20 })
  {
    passed = checkGather(controller, piece, whole->GetOutput(), { 0, 1 }, roundBytes) && passed;
    passed = checkGather(controller, piece, whole->GetOutput(), { rank, ranks }, roundBytes) && passed;
  }
  const int status = opaltest::rankVerdict(controller, passed, "TestOpalGatherRounds");
  controller->Finalize();
  return status;
}
