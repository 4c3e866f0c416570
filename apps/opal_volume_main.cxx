// opal-volume: builds the opal volume and writes it as a .vti file, with a
// one-screen summary of what was built.
#include "OpalAtomicFile.h"
#include "OpalCliFiles.h"
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalPresets.h"
#include "OpalVolumeBuild.h"
#include "OpalVtkSupport.h"
#include "vtkOpalSource.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <CLI/CLI.hpp>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>

int main(int argc, char** argv)
{
  CLI::App app{ "Builds the volumetric opal model of Nakajima & Kawai and writes it as VTK image data." };
  OpalModelOptions model;
  model.addTo(app);
  std::string output = "opal.vti";
  app.add_option("-o,--output", output, "Output .vti file")->check(fileExtension({ ".vti" }))->capture_default_str();
  app.failure_message([](const CLI::App* a, const CLI::Error& e) { return oneLineFailure("opal-volume", e.what(), a); });
  if (const int status = parseArguments(app, argc, argv); status >= 0)
  {
    return status;
  }
  // A full disk or a file-size limit then fails the write (and is reported)
  // instead of killing the process half way through a file.
  std::signal(SIGXFSZ, SIG_IGN);
  installStderrOutputWindow("opal-volume");

  vtkNew<vtkOpalSource> source;
  // The preset first: choosing it sets its values, which the flags then replace.
  source->SetPreset(model.presetIndex());
  source->SetModelParameters(model.parameters());
  for (const std::string& error :
    { opal::validate(source->GetModelParameters()), opal::volumeMemoryError(source->GetModelParameters()) })
  {
    if (!error.empty())
    {
      std::cerr << "opal-volume: " << error << std::endl;
      return 2;
    }
  }
  ProgressBar bar("volume");
  showProgress(source, bar);
  const auto start = std::chrono::steady_clock::now();
  if (!source->GetExecutive()->Update())
  {
    std::cerr << "opal-volume: the volume could not be built." << std::endl;
    return 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkImageData* volume = source->GetOutput();

  std::array<long long, 3> counts{ 0, 0, 0 };
  vtkDataArray* types = volume->GetPointData()->GetArray("VoxelType");
  for (vtkIdType i = 0; i < types->GetNumberOfTuples(); ++i)
  {
    ++counts[static_cast<std::size_t>(types->GetComponent(i, 0)) % 3];
  }
  const int placed = static_cast<int>(volume->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0));
  std::string error;
  {
    const SignalsHeld held; // a signal while writing is delivered once the file is whole or gone
    error = writeImageDataFile(output, volume);
  }
  if (!error.empty())
  {
    std::cerr << "opal-volume: " << error << std::endl;
    return 1;
  }

  int dims[3];
  volume->GetDimensions(dims);
  const opal::PresetSettings* recorded = opal::presetByIndex(model.presetIndex());
  std::printf("Opal volume (preset %s)\n", recorded ? recorded->Name : "custom");
  std::printf("  grid             %d x %d x %d voxels (%lld)\n", dims[0], dims[1], dims[2],
    counts[0] + counts[1] + counts[2]);
  std::printf("  empty            %lld\n", counts[0]);
  std::printf("  scattering       %lld\n", counts[1]);
  std::printf("  diffraction      %lld\n", counts[2]);
  if (source->GetDomainLayout() == static_cast<int>(opal::DomainLayoutKind::Voronoi))
  {
    std::printf("  voronoi cells    %d, %d ordered (domains)\n", source->GetVoronoiCellCount(), placed);
  }
  else
  {
    std::printf("  domains placed   %d of %d\n", placed, source->GetDomainCount());
  }
  std::printf("  build time       %.3f s\n", seconds);
  std::printf("  written to       %s\n", output.c_str());
  return 0;
}
