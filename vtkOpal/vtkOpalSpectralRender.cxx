#include "vtkOpalSpectralRender.h"

#include "OpalRenderParameters.h"
#include "OpalSpectralRenderer.h"
#include "OpalVulkanError.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpalArrayCopy.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkOpalSpectralRender);

namespace
{
using vtkOpalArrayCopy::copy;

// The input's float (or int) values as a contiguous vector of the wanted type.
template <typename T>
std::vector<T> valuesOf(vtkDataArray* array)
{
  std::vector<T> values(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    values[static_cast<std::size_t>(i)] = static_cast<T>(array->GetComponent(i, 0));
  }
  return values;
}
} // namespace

vtkOpalSpectralRender::vtkOpalSpectralRender()
{
  this->SetRenderParameters(opal::RenderParameters());
  this->DeviceIndex = -1;
  this->DeviceMemoryLimit = 0;
}

vtkOpalSpectralRender::~vtkOpalSpectralRender() = default;

opal::RenderParameters vtkOpalSpectralRender::GetRenderParameters() const
{
  opal::RenderParameters p;
  copy(this->ImageSize, p.ImageSize);
  copy(this->ImageRegion, p.ImageRegion);
  copy(this->EyePosition, p.EyePosition);
  copy(this->FocalPoint, p.FocalPoint);
  copy(this->ViewUp, p.ViewUp);
  p.ViewAngle = this->ViewAngle;
  copy(this->LightPosition, p.LightPosition);
  p.LightRadius = this->LightRadius;
  copy(this->ModelRotation, p.ModelRotation);
  copy(this->WavelengthRange, p.WavelengthRange);
  p.WavelengthStep = this->WavelengthStep;
  p.RefractiveIndex = this->RefractiveIndex;
  p.BraggBandwidth = this->BraggBandwidth;
  p.DiffractionGain = this->DiffractionGain;
  p.BraggOrders = this->BraggOrders;
  p.MosaicSpread = this->MosaicSpread;
  p.Exposure = this->Exposure;
  copy(this->Background, p.Background);
  p.StepSize = this->StepSize;
  p.SpecularSamples = this->SpecularSamples;
  p.LightFalloffAtEntry = this->LightFalloffAtEntry;
  p.WriteSpectrum = this->WriteSpectrum;
  return p;
}

void vtkOpalSpectralRender::SetRenderParameters(const opal::RenderParameters& p)
{
  copy(p.ImageSize, this->ImageSize);
  copy(p.ImageRegion, this->ImageRegion);
  copy(p.EyePosition, this->EyePosition);
  copy(p.FocalPoint, this->FocalPoint);
  copy(p.ViewUp, this->ViewUp);
  this->ViewAngle = p.ViewAngle;
  copy(p.LightPosition, this->LightPosition);
  this->LightRadius = p.LightRadius;
  copy(p.ModelRotation, this->ModelRotation);
  copy(p.WavelengthRange, this->WavelengthRange);
  this->WavelengthStep = p.WavelengthStep;
  this->RefractiveIndex = p.RefractiveIndex;
  this->BraggBandwidth = p.BraggBandwidth;
  this->DiffractionGain = p.DiffractionGain;
  this->BraggOrders = p.BraggOrders;
  this->MosaicSpread = p.MosaicSpread;
  this->Exposure = p.Exposure;
  copy(p.Background, this->Background);
  this->StepSize = p.StepSize;
  this->SpecularSamples = p.SpecularSamples;
  this->LightFalloffAtEntry = p.LightFalloffAtEntry;
  this->WriteSpectrum = p.WriteSpectrum;
  this->Modified();
}

int vtkOpalSpectralRender::GetNumberOfValidationMessages() const
{
  return this->ValidationMessages;
}

int vtkOpalSpectralRender::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkOpalSpectralRender::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const opal::RenderParameters p = this->GetRenderParameters();
  const std::string error = opal::validate(p);
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  // VTK image rows run bottom to top; ImageRegion counts from the top.
  const int width = p.ImageRegion[2] > 0 ? p.ImageRegion[2] : p.ImageSize[0] - p.ImageRegion[0];
  const int height = p.ImageRegion[3] > 0 ? p.ImageRegion[3] : p.ImageSize[1] - p.ImageRegion[1];
  const int top = p.ImageSize[1] - 1 - p.ImageRegion[1];
  const int wholeExtent[6] = { p.ImageRegion[0], p.ImageRegion[0] + width - 1, top - height + 1, top, 0, 0 };
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent, 6);
  const double spacing[3] = { 1, 1, 1 };
  const double origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

int vtkOpalSpectralRender::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A request left over from an earlier image size (after a failed update)
  // is clipped to the image; one outside it asks for the whole image.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6], requested[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), requested);
  bool overlaps = true;
  for (int a = 0; a < 3; ++a)
  {
    requested[2 * a] = std::max(requested[2 * a], whole[2 * a]);
    requested[2 * a + 1] = std::min(requested[2 * a + 1], whole[2 * a + 1]);
    overlaps = overlaps && requested[2 * a] <= requested[2 * a + 1];
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), overlaps ? requested : whole, 6);

  // Every pixel may look through the whole volume: ask for all of it, as one
  // piece, whichever piece of the image this process renders.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  int wholeExtent[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), wholeExtent, 6);
  return 1;
}

int vtkOpalSpectralRender::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!input)
  {
    vtkErrorMacro("The input is not image data; connect an Opal Volume.");
    return 0;
  }

  opal::RenderVolume volume;
  int dims[3];
  input->GetDimensions(dims);
  double origin[3], spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  int inputExtent[6];
  input->GetExtent(inputExtent);
  for (int a = 0; a < 3; ++a)
  {
    volume.Dimensions[static_cast<std::size_t>(a)] = dims[a];
    volume.Origin[static_cast<std::size_t>(a)] = origin[a] + inputExtent[2 * a] * spacing[a];
    volume.Spacing[static_cast<std::size_t>(a)] = spacing[a];
  }
  vtkPointData* pd = input->GetPointData();
  for (const char* name : { "ScatteringCoefficient", "DomainId", "SurfaceDistance", "Normal", "ParticleDiameter" })
  {
    if (!pd->GetArray(name))
    {
      vtkErrorMacro("The input lacks the point array " << name << "; connect an Opal Volume.");
      return 0;
    }
  }
  const std::vector<float> scattering = valuesOf<float>(pd->GetArray("ScatteringCoefficient"));
  const std::vector<std::int32_t> domainIds = valuesOf<std::int32_t>(pd->GetArray("DomainId"));
  const std::vector<float> distance = valuesOf<float>(pd->GetArray("SurfaceDistance"));
  volume.ScatteringCoefficient = scattering.data();
  volume.DomainId = domainIds.data();
  volume.SurfaceDistance = distance.data();
  // The domain table: each domain's lattice normal and FCC (111) spacing d = sqrt(2/3) l (eq. 3).
  vtkDataArray* normals = pd->GetArray("Normal");
  vtkDataArray* diameters = pd->GetArray("ParticleDiameter");
  for (std::size_t i = 0; i < domainIds.size(); ++i)
  {
    const int id = domainIds[i];
    if (id < 0)
    {
      continue;
    }
    if (static_cast<std::size_t>(id) >= volume.Domains.size())
    {
      volume.Domains.resize(static_cast<std::size_t>(id) + 1, { 0.0f, 1.0f, 0.0f, 0.0f });
    }
    auto& domain = volume.Domains[static_cast<std::size_t>(id)];
    if (domain[3] == 0.0f)
    {
      double n[3];
      normals->GetTuple(static_cast<vtkIdType>(i), n);
      domain = { static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]),
        static_cast<float>(std::sqrt(2.0 / 3.0) * diameters->GetComponent(static_cast<vtkIdType>(i), 0)) };
    }
  }

  // Render the requested rows and columns (VTK's bottom-up rows to the renderer's top-down).
  opal::RenderParameters p = this->GetRenderParameters();
  int extent[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  if (extent[1] < extent[0] || extent[3] < extent[2])
  {
    output->Initialize();
    return 1;
  }
  p.ImageRegion = { extent[0], p.ImageSize[1] - 1 - extent[3], extent[1] - extent[0] + 1, extent[3] - extent[2] + 1 };

  opal::RenderImage image;
  try
  {
    if (!this->Renderer || this->RendererDeviceIndex != this->DeviceIndex ||
      this->RendererMemoryLimit != this->DeviceMemoryLimit)
    {
      this->Renderer.reset();
      opal::VulkanOptions options;
      options.DeviceIndex = this->DeviceIndex;
      options.MemoryLimitBytes = static_cast<std::uint64_t>(std::max(0, this->DeviceMemoryLimit)) << 20;
      this->Renderer = std::make_unique<opal::SpectralRenderer>(options);
      this->RendererDeviceIndex = this->DeviceIndex;
      this->RendererMemoryLimit = this->DeviceMemoryLimit;
    }
    image = this->Renderer->render(volume, p, [this](double fraction) {
      this->UpdateProgress(fraction);
      return !this->GetAbortExecute();
    });
    this->ValidationMessages = static_cast<int>(this->Renderer->context().validationMessages().size());
  }
  catch (const opal::NoVulkanDeviceError& e)
  {
    vtkErrorMacro("No Vulkan device: " << e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  if (image.ImageSize[0] == 0)
  {
    output->Initialize(); // aborted
    return 0;
  }

  output->SetExtent(extent);
  const int width = image.Region[2];
  const int height = image.Region[3];
  const vtkIdType count = static_cast<vtkIdType>(width) * height;
  const int wavelengths = static_cast<int>(image.Wavelengths.size());
  auto makeArray = [count](auto array, const char* name, int components) {
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(count);
    return array;
  };
  vtkNew<vtkUnsignedCharArray> rgb;
  vtkNew<vtkFloatArray> radiance, xyz, dominant, depth, spectrum;
  makeArray(rgb.Get(), "RGB", 3);
  makeArray(radiance.Get(), "Radiance", 3);
  makeArray(xyz.Get(), "XYZ", 3);
  makeArray(dominant.Get(), "DominantBraggWavelength", 1);
  makeArray(depth.Get(), "Depth", 1);
  if (p.WriteSpectrum)
  {
    makeArray(spectrum.Get(), "Spectrum", wavelengths);
  }
  for (int row = 0; row < height; ++row)
  {
    // Image row `row` (from the top) is VTK row height - 1 - row of the extent.
    const std::size_t from = static_cast<std::size_t>(row) * width;
    const std::size_t to = static_cast<std::size_t>(height - 1 - row) * width;
    std::copy_n(&image.RGB[3 * from], 3 * width, rgb->GetPointer(static_cast<vtkIdType>(3 * to)));
    std::copy_n(&image.Radiance[3 * from], 3 * width, radiance->GetPointer(static_cast<vtkIdType>(3 * to)));
    std::copy_n(&image.XYZ[3 * from], 3 * width, xyz->GetPointer(static_cast<vtkIdType>(3 * to)));
    std::copy_n(&image.DominantBraggWavelength[from], width, dominant->GetPointer(static_cast<vtkIdType>(to)));
    std::copy_n(&image.Depth[from], width, depth->GetPointer(static_cast<vtkIdType>(to)));
    if (p.WriteSpectrum)
    {
      std::copy_n(&image.Spectrum[from * wavelengths], static_cast<std::size_t>(width) * wavelengths,
        spectrum->GetPointer(static_cast<vtkIdType>(to * wavelengths)));
    }
  }
  vtkPointData* outPD = output->GetPointData();
  outPD->SetScalars(rgb);
  outPD->AddArray(radiance);
  outPD->AddArray(xyz);
  outPD->AddArray(dominant);
  outPD->AddArray(depth);
  if (p.WriteSpectrum)
  {
    outPD->AddArray(spectrum);
  }
  vtkNew<vtkDoubleArray> lambdas;
  lambdas->SetName("Wavelengths");
  for (double lambda : image.Wavelengths)
  {
    lambdas->InsertNextValue(lambda);
  }
  output->GetFieldData()->AddArray(lambdas);
  vtkNew<vtkDoubleArray> exposure;
  exposure->SetName("Exposure");
  exposure->InsertNextValue(image.Exposure);
  output->GetFieldData()->AddArray(exposure);
  vtkNew<vtkStringArray> device;
  device->SetName("VulkanDevice");
  device->InsertNextValue(this->Renderer->context().deviceName());
  output->GetFieldData()->AddArray(device);
  vtkNew<vtkDoubleArray> timings;
  timings->SetName("RenderTimings");
  timings->SetNumberOfComponents(6);
  timings->SetComponentName(0, "Setup");
  timings->SetComponentName(1, "Upload");
  timings->SetComponentName(2, "LightPass");
  timings->SetComponentName(3, "March");
  timings->SetComponentName(4, "Colour");
  timings->SetComponentName(5, "Readback");
  const double t[6] = { image.Timings.Setup, image.Timings.Upload, image.Timings.LightPass, image.Timings.March,
    image.Timings.Colour, image.Timings.Readback };
  timings->InsertNextTuple(t);
  output->GetFieldData()->AddArray(timings);
  return 1;
}

void vtkOpalSpectralRender::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "EyePosition: " << this->EyePosition[0] << " " << this->EyePosition[1] << " "
     << this->EyePosition[2] << "\n";
  os << indent << "LightPosition: " << this->LightPosition[0] << " " << this->LightPosition[1] << " "
     << this->LightPosition[2] << "\n";
  os << indent << "ModelRotation: " << this->ModelRotation[0] << " " << this->ModelRotation[1] << " "
     << this->ModelRotation[2] << "\n";
  os << indent << "WavelengthRange: " << this->WavelengthRange[0] << " - " << this->WavelengthRange[1]
     << " step " << this->WavelengthStep << "\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "BraggBandwidth: " << this->BraggBandwidth << "\n";
  os << indent << "DiffractionGain: " << this->DiffractionGain << "\n";
  os << indent << "MosaicSpread: " << this->MosaicSpread << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "StepSize: " << this->StepSize << "\n";
  os << indent << "DeviceIndex: " << this->DeviceIndex << "\n";
}
