// Small opal volumes and array comparisons shared by the C++ tests.
#pragma once

#include "OpalTestHarness.h"
#include "vtkOpalSource.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSmartPointer.h"

#include <array>
#include <string>

namespace opaltest
{

// The array names of docs/design.md §2.5: the interface users and tests rely on.
inline const std::array<const char*, 9>& volumeArrayNames()
{
  static const std::array<const char*, 9> names = { "VoxelType", "ParticleDiameter", "Normal",
    "DomainId", "BraggLambdaMax", "BraggLambdaMin", "ScatteringCoefficient", "SurfaceDistance",
    "LatticeOrientation" };
  return names;
}

// A quarter-resolution opal (40 x 20 x 50 voxels of 0.4 mm) with a few domains.
inline vtkSmartPointer<vtkOpalSource> makeSmallSource(int seed = 1)
{
  auto source = vtkSmartPointer<vtkOpalSource>::New();
  source->SetDimensions(40, 20, 50);
  source->SetDomainCount(30);
  source->SetSeed(seed);
  return source;
}

// A small volume of Voronoi grains with correlated scattering diameters.
inline vtkSmartPointer<vtkOpalSource> makeSmallGrainSource(int seed = 1)
{
  auto source = makeSmallSource(seed);
  source->SetDomainLayout(1);
  source->SetVoronoiCellCount(80);
  source->SetDiameterCorrelationLength(0.7);
  return source;
}

// Counts the points of `piece` whose arrays differ from `whole` at the same global index.
inline long long countDifferences(vtkImageData* whole, vtkImageData* piece, const std::string& name)
{
  vtkDataArray* wholeArray = whole->GetPointData()->GetArray(name.c_str());
  vtkDataArray* pieceArray = piece->GetPointData()->GetArray(name.c_str());
  if (!wholeArray || !pieceArray || wholeArray->GetNumberOfComponents() != pieceArray->GetNumberOfComponents())
  {
    return -1;
  }
  int extent[6];
  piece->GetExtent(extent);
  long long differences = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        const vtkIdType a = whole->ComputePointId(ijk);
        const vtkIdType b = piece->ComputePointId(ijk);
        for (int c = 0; c < wholeArray->GetNumberOfComponents(); ++c)
        {
          if (wholeArray->GetComponent(a, c) != pieceArray->GetComponent(b, c))
          {
            ++differences;
            break;
          }
        }
      }
    }
  }
  return differences;
}

// A Filter fed image data that is not an opal volume (VTK's wavelet): the
// request fails and the error names `missingArray`.
template <typename Filter>
void checkRefusesNonOpalVolume(const std::string& missingArray)
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  vtkNew<Filter> filter;
  filter->SetInputConnection(wavelet->GetOutputPort());
  vtkNew<MessageRecorder> recorder;
  recorder->watch(filter);
  OPAL_CHECK(filter->GetExecutive()->Update() == 0, "a volume without the opal arrays fails");
  OPAL_CHECK(recorder->anyContains(recorder->Errors, missingArray), "the message names the missing array " + missingArray);
}
} // namespace opaltest
