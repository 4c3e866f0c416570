// opal-volume: builds the opal volume and writes it as a .vti file, or as a
// partitioned .pvti built and written piece by piece, with a one-screen
// summary of what was built.
#include "OpalAtomicFile.h"
#include "OpalCliFiles.h"
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalPresets.h"
#include "OpalVolumeBuild.h"
#include "OpalVtkSupport.h"
#include "vtkOpalSource.h"

#include "vtkDataArray.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>

namespace
{
// What the summary reports, gathered from each piece the source builds.
struct BuiltCounts
{
  std::array<long long, 3> VoxelTypes{ 0, 0, 0 }; // empty, scattering, diffraction
  int DomainsPlaced = 0;
};

// Adds the voxel types of the points `piece` owns: a point on a piece's upper
// face belongs to the piece above it, unless it is on the grid's own.
void countPiece(vtkImageData* piece, const int whole[6], BuiltCounts& counts)
{
  int extent[6];
  piece->GetExtent(extent);
  counts.DomainsPlaced = static_cast<int>(piece->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0));
  vtkDataArray* types = piece->GetPointData()->GetArray("VoxelType"); // none with --arrays render
  vtkIdType ijk[3];
  for (ijk[2] = extent[4]; types && ijk[2] <= extent[5]; ++ijk[2])
    for (ijk[1] = extent[2]; ijk[1] <= extent[3]; ++ijk[1])
      for (ijk[0] = extent[0]; ijk[0] <= extent[1]; ++ijk[0])
      {
        bool owned = true;
        for (int a = 0; a < 3; ++a)
        {
          owned = owned && (ijk[a] < extent[2 * a + 1] || extent[2 * a + 1] == whole[2 * a + 1]);
        }
        if (owned)
        {
          const vtkIdType point = (ijk[0] - extent[0]) +
            (extent[1] - extent[0] + 1) * ((ijk[1] - extent[2]) + (extent[3] - extent[2] + 1) * (ijk[2] - extent[4]));
          ++counts.VoxelTypes[static_cast<std::size_t>(types->GetComponent(point, 0)) % 3];
        }
      }
}

// Counts every piece the source builds (the whole grid is one piece).
void countEachPiece(vtkOpalSource* source, BuiltCounts& counts)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(&counts);
  command->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    auto* built = static_cast<vtkOpalSource*>(caller);
    int whole[6];
    built->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    if (built->GetOutput()->GetNumberOfPoints() > 0)
    {
      countPiece(built->GetOutput(), whole, *static_cast<BuiltCounts*>(client));
    }
  });
  source->AddObserver(vtkCommand::EndEvent, command);
}

// Builds the volume and writes it: a .vti whole, a .pvti piece by piece.
// Empty string on success, else the reason.
std::string buildAndWrite(vtkOpalSource* source, const std::string& output, int pieces)
{
  if (lowerCaseExtension(output) == ".pvti")
  {
    return writePartitionedImageDataFile(output, source, pieces);
  }
  if (!source->GetExecutive()->Update())
  {
    return "the volume could not be built.";
  }
  const SignalsHeld held; // a signal while writing is delivered once the file is whole or gone
  return writeImageDataFile(output, source->GetOutput());
}

// The voxels of the largest piece, as VTK's partitioned writer splits the grid.
std::uint64_t largestPiece(const std::array<int, 3>& dims, int pieces)
{
  int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  std::uint64_t largest = 0;
  vtkNew<vtkExtentTranslator> translator;
  for (int piece = 0; piece < pieces; ++piece)
  {
    int extent[6];
    translator->PieceToExtentThreadSafe(piece, pieces, 0, whole, extent, vtkExtentTranslator::BLOCK_MODE, 0);
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a)
    {
      voxels *= static_cast<std::uint64_t>(std::max(extent[2 * a + 1] - extent[2 * a] + 1, 0));
    }
    largest = std::max(largest, voxels);
  }
  return largest;
}

void printSummary(vtkOpalSource* source, const OpalModelOptions& model, const BuiltCounts& counts, double seconds,
  const std::string& output, int pieces)
{
  const opal::ModelParameters parameters = source->GetModelParameters();
  const std::array<int, 3>& dims = parameters.Dimensions;
  const std::array<long long, 3>& types = counts.VoxelTypes;
  const opal::PresetSettings* recorded = opal::presetByIndex(model.presetIndex());
  std::printf("Opal volume (preset %s)\n", recorded ? recorded->Name : "custom");
  std::printf("  grid             %d x %d x %d voxels (%lld)\n", dims[0], dims[1], dims[2],
    static_cast<long long>(dims[0]) * dims[1] * dims[2]);
  if (source->GetOutputArrays() == vtkOpalSource::ALL_ARRAYS)
  {
    std::printf("  empty            %lld\n", types[0]);
    std::printf("  scattering       %lld\n", types[1]);
    std::printf("  diffraction      %lld\n", types[2]);
  }
  else
  {
    std::printf("  arrays           the render's only (no VoxelType to count)\n");
  }
  if (source->GetDomainLayout() == static_cast<int>(opal::DomainLayoutKind::Voronoi))
  {
    std::printf("  voronoi cells    %d, %d ordered (domains)\n", source->GetVoronoiCellCount(), counts.DomainsPlaced);
  }
  else
  {
    std::printf("  domains placed   %d of %d\n", counts.DomainsPlaced, source->GetDomainCount());
  }
  std::printf("  build and write  %.3f s\n", seconds);
  std::printf("  written to       %s%s\n", output.c_str(),
    pieces > 1 ? (" (" + std::to_string(pieces) + " pieces)").c_str() : "");
}
} // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "Builds the volumetric opal model of Nakajima & Kawai and writes it as VTK image data." };
  OpalModelOptions model;
  model.addTo(app);
  std::string output = "opal.vti";
  app.add_option("-o,--output", output, "Output .vti file, or .pvti: a partitioned volume, one .vti per piece beside it")
    ->check(fileExtension({ ".vti", ".pvti" }))
    ->capture_default_str();
  int pieces = 0;
  CLI::Option* piecesOption = app.add_option("--pieces", pieces,
    "Pieces of a .pvti output (default 4), each built and written alone, as ParaView's ranks read them");
  piecesOption->check(CLI::Range(1, 4096));
  std::string arrays = "all";
  app.add_option("--arrays", arrays,
       "Point arrays to write: all, or render (only what the render reads, 12 bytes per voxel instead of 53)")
    ->check(CLI::IsMember({ "all", "render" }))
    ->capture_default_str();
  app.failure_message([](const CLI::App* a, const CLI::Error& e) { return oneLineFailure("opal-volume", e.what(), a); });
  if (const int status = parseArguments(app, argc, argv); status >= 0)
  {
    return status;
  }
  const bool partitioned = lowerCaseExtension(output) == ".pvti";
  if (!partitioned && piecesOption->count() > 0)
  {
    std::cerr << "opal-volume: --pieces needs a .pvti output; " << output << " is one .vti file." << std::endl;
    return 2;
  }
  pieces = partitioned ? (pieces > 0 ? pieces : 4) : 1;
  // A full disk or a file-size limit then fails the write (and is reported)
  // instead of killing the process half way through a file.
  std::signal(SIGXFSZ, SIG_IGN);
  installStderrOutputWindow("opal-volume");

  vtkNew<vtkOpalSource> source;
  // The preset first: choosing it sets its values, which the flags then replace.
  source->SetPreset(model.presetIndex());
  source->SetModelParameters(model.parameters());
  const bool renderOnly = arrays == "render";
  source->SetOutputArrays(renderOnly ? vtkOpalSource::RENDER_ARRAYS : vtkOpalSource::ALL_ARRAYS);
  // A .pvti's pieces are built one at a time: the memory a piece needs.
  const opal::ModelParameters parameters = source->GetModelParameters();
  for (const std::string& error : { opal::validate(parameters),
         opal::volumeMemoryError(parameters, renderOnly ? opal::VolumeArrays::Render : opal::VolumeArrays::All,
           largestPiece(parameters.Dimensions, pieces)) })
  {
    if (!error.empty())
    {
      std::cerr << "opal-volume: " << error << std::endl;
      return 2;
    }
  }
  ProgressBar bar("volume");
  showProgress(source, bar, pieces);
  BuiltCounts counts;
  countEachPiece(source, counts);
  const auto start = std::chrono::steady_clock::now();
  const std::string error = buildAndWrite(source, output, pieces);
  if (!error.empty())
  {
    std::cerr << "opal-volume: " << error << std::endl;
    return 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printSummary(source, model, counts, seconds, output, pieces);
  return 0;
}
