#include "vtkOpalBraggMap.h"

#include "OpalBraggMap.h"
#include "OpalParallel.h"

#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

vtkStandardNewMacro(vtkOpalBraggMap);

vtkOpalBraggMap::vtkOpalBraggMap()
{
  const opal::BraggMapSettings defaults;
  std::copy(defaults.LightPosition.begin(), defaults.LightPosition.end(), this->LightPosition);
  std::copy(defaults.EyePosition.begin(), defaults.EyePosition.end(), this->EyePosition);
  this->RefractiveIndex = defaults.RefractiveIndex;
  this->BraggOrder = defaults.Order;
  this->MosaicSpread = defaults.MosaicSpread;
}

int vtkOpalBraggMap::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkOpalBraggMap::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* output = vtkDataSet::GetData(outputVector);
  output->ShallowCopy(input);

  if (!(this->RefractiveIndex > 1) || this->BraggOrder < 1 || !(this->MosaicSpread >= 0))
  {
    vtkErrorMacro("RefractiveIndex must exceed 1, BraggOrder be at least 1 and MosaicSpread not negative.");
    return 0;
  }
  // The volume carries the domains on its points, the layout on its cells.
  const bool onPoints = input->GetPointData()->GetArray("DomainId") != nullptr;
  vtkDataSetAttributes* attributes =
    onPoints ? static_cast<vtkDataSetAttributes*>(input->GetPointData()) : input->GetCellData();
  for (const char* name : { "DomainId", "Normal", "ParticleDiameter" })
  {
    if (!attributes->GetArray(name))
    {
      vtkErrorMacro("The input lacks the " << (onPoints ? "point" : "cell") << " array " << name
                                           << "; connect an Opal Volume or its domain polygons.");
      return 0;
    }
  }
  if (vtkImageData* image = vtkImageData::SafeDownCast(input))
  {
    vtkDataArray* distance = image->GetPointData()->GetArray("SurfaceDistance");
    const vtkIdType nearest = image->FindPoint(this->LightPosition);
    if (distance && nearest >= 0 && distance->GetComponent(nearest, 0) <= 0)
    {
      vtkErrorMacro("LightPosition (" << this->LightPosition[0] << ", " << this->LightPosition[1] << ", "
                                      << this->LightPosition[2] << ") is inside the opal; place the light outside it.");
      return 0;
    }
  }

  opal::BraggMapSettings settings;
  std::copy(this->LightPosition, this->LightPosition + 3, settings.LightPosition.begin());
  std::copy(this->EyePosition, this->EyePosition + 3, settings.EyePosition.begin());
  settings.RefractiveIndex = this->RefractiveIndex;
  settings.Order = this->BraggOrder;
  settings.MosaicSpread = this->MosaicSpread;

  vtkDataArray* ids = attributes->GetArray("DomainId");
  vtkDataArray* normals = attributes->GetArray("Normal");
  vtkDataArray* diameters = attributes->GetArray("ParticleDiameter");
  const vtkIdType count = ids->GetNumberOfTuples();
  vtkNew<vtkFloatArray> wavelength, visible;
  vtkNew<vtkUnsignedCharArray> colour;
  wavelength->SetName("BraggWavelength");
  wavelength->SetNumberOfTuples(count);
  visible->SetName("BraggVisible");
  visible->SetNumberOfTuples(count);
  colour->SetName("BraggColor");
  colour->SetNumberOfComponents(3);
  colour->SetNumberOfTuples(count);
  // Cell centres need a thread-safe GetCell: build the links once.
  if (!onPoints && count > 0)
  {
    vtkNew<vtkIdList> warmUp;
    input->GetCellPoints(0, warmUp);
  }

  const int chunks = 20;
  const vtkIdType chunk = std::max<vtkIdType>(1, (count + chunks - 1) / chunks);
  for (vtkIdType begin = 0; begin < count; begin += chunk)
  {
    if (this->GetAbortExecute())
    {
      return 0;
    }
    const vtkIdType end = std::min(count, begin + chunk);
    opal::parallelFor(static_cast<int>(begin), static_cast<int>(end), [&](int first, int last) {
      vtkNew<vtkIdList> cellPoints;
      for (vtkIdType i = first; i < last; ++i)
      {
        opal::BraggMapValue value;
        if (ids->GetComponent(i, 0) >= 0)
        {
          std::array<double, 3> position{ 0, 0, 0 }, normal;
          if (onPoints)
          {
            input->GetPoint(i, position.data());
          }
          else
          {
            input->GetCellPoints(i, cellPoints);
            for (vtkIdType k = 0; k < cellPoints->GetNumberOfIds(); ++k)
            {
              double x[3];
              input->GetPoint(cellPoints->GetId(k), x);
              for (int a = 0; a < 3; ++a)
              {
                position[static_cast<std::size_t>(a)] += x[a] / cellPoints->GetNumberOfIds();
              }
            }
          }
          normals->GetTuple(i, normal.data());
          value = opal::braggMapAt(position, normal, diameters->GetComponent(i, 0), settings);
        }
        wavelength->SetValue(i, static_cast<float>(value.Wavelength));
        visible->SetValue(i, static_cast<float>(value.Visible));
        colour->SetTypedTuple(i, value.Colour.data());
      }
    });
    this->UpdateProgress(static_cast<double>(end) / count);
  }
  vtkDataSetAttributes* outAttributes = onPoints ? static_cast<vtkDataSetAttributes*>(output->GetPointData())
                                                 : output->GetCellData();
  outAttributes->AddArray(wavelength);
  outAttributes->AddArray(visible);
  outAttributes->AddArray(colour);
  return 1;
}

void vtkOpalBraggMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LightPosition: " << this->LightPosition[0] << " " << this->LightPosition[1] << " "
     << this->LightPosition[2] << "\n";
  os << indent << "EyePosition: " << this->EyePosition[0] << " " << this->EyePosition[1] << " "
     << this->EyePosition[2] << "\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "BraggOrder: " << this->BraggOrder << "\n";
  os << indent << "MosaicSpread: " << this->MosaicSpread << "\n";
}
