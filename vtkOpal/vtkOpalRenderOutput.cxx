#include "vtkOpalRenderOutput.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkTypeUInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

namespace
{
// A point array of the image's pixels from per-pixel values in the render's
// top-down rows.
template <typename ArrayT, typename T>
vtkNew<ArrayT> pointArray(const char* name, const std::vector<T>& values, int components, int width, int height)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(components);
  for (int y = 0; y < height; ++y)
  {
    // Image row y (from the top) is VTK row height - 1 - y.
    std::copy_n(values.data() + static_cast<std::size_t>(y) * row, row,
      array->GetPointer(static_cast<vtkIdType>(static_cast<std::size_t>(height - 1 - y) * row)));
  }
  return array;
}

void addFieldData(const opal::RenderImage& image, const std::string& deviceName, vtkFieldData* fields)
{
  vtkNew<vtkDoubleArray> wavelengths;
  wavelengths->SetName("Wavelengths");
  for (double lambda : image.Wavelengths)
  {
    wavelengths->InsertNextValue(lambda);
  }
  fields->AddArray(wavelengths);
  vtkNew<vtkDoubleArray> exposure;
  exposure->SetName("Exposure");
  exposure->InsertNextValue(image.Exposure);
  fields->AddArray(exposure);
  vtkNew<vtkStringArray> illuminant;
  illuminant->SetName("Illuminant");
  illuminant->InsertNextValue(image.Illuminant);
  fields->AddArray(illuminant);
  vtkNew<vtkDoubleArray> illuminantScale;
  illuminantScale->SetName("IlluminantScale");
  illuminantScale->InsertNextValue(image.IlluminantScale);
  fields->AddArray(illuminantScale);
  vtkNew<vtkStringArray> orders;
  orders->SetName("ScatteringOrders");
  orders->InsertNextValue(image.ScatteringOrders);
  fields->AddArray(orders);
  vtkNew<vtkStringArray> device;
  device->SetName("VulkanDevice");
  device->InsertNextValue(deviceName);
  fields->AddArray(device);
  vtkNew<vtkDoubleArray> timings;
  timings->SetName("RenderTimings");
  const opal::RenderTimings& t = image.Timings;
  const double values[8] = { t.Setup, t.Upload, t.LightPass, t.ScatteredLight, t.March, t.MarchRounds, t.Colour,
    t.Readback };
  const char* names[8] = { "Setup", "Upload", "LightPass", "ScatteredLight", "March", "MarchRounds", "Colour",
    "Readback" };
  timings->SetNumberOfComponents(8);
  for (int c = 0; c < 8; ++c)
  {
    timings->SetComponentName(c, names[c]);
  }
  timings->InsertNextTuple(values);
  fields->AddArray(timings);
  vtkNew<vtkTypeUInt64Array> devicePeak;
  devicePeak->SetName("DeviceMemoryPeak");
  devicePeak->InsertNextValue(image.DeviceMemoryPeak);
  fields->AddArray(devicePeak);
}
} // namespace

namespace vtkOpalRenderOutput
{
void ExtentOf(const opal::RenderImage& image, int extent[6])
{
  const int top = image.ImageSize[1] - 1 - image.Region[1];
  extent[0] = image.Region[0];
  extent[1] = image.Region[0] + image.Region[2] - 1;
  extent[2] = top - image.Region[3] + 1;
  extent[3] = top;
  extent[4] = extent[5] = 0;
}

void Fill(const opal::RenderImage& image, const std::string& deviceName, vtkImageData* output)
{
  int extent[6];
  ExtentOf(image, extent);
  output->Initialize();
  output->SetExtent(extent);
  output->SetOrigin(0.0, 0.0, 0.0); // pixel units, as RequestInformation announces
  output->SetSpacing(1.0, 1.0, 1.0);
  const int w = image.Region[2], h = image.Region[3];
  vtkPointData* pd = output->GetPointData();
  pd->SetScalars(pointArray<vtkUnsignedCharArray>("RGB", image.RGB, 3, w, h));
  pd->AddArray(pointArray<vtkFloatArray>("Radiance", image.Radiance, 3, w, h));
  pd->AddArray(pointArray<vtkFloatArray>("XYZ", image.XYZ, 3, w, h));
  pd->AddArray(pointArray<vtkFloatArray>("DominantBraggWavelength", image.DominantBraggWavelength, 1, w, h));
  pd->AddArray(pointArray<vtkFloatArray>("Depth", image.Depth, 1, w, h));
  if (!image.Spectrum.empty())
  {
    pd->AddArray(
      pointArray<vtkFloatArray>("Spectrum", image.Spectrum, static_cast<int>(image.Wavelengths.size()), w, h));
  }
  addFieldData(image, deviceName, output->GetFieldData());
}
} // namespace vtkOpalRenderOutput
