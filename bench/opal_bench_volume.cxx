// Bench: generate the paper-scale opal volume (160 x 80 x 200 voxels, 250
// domains) and print the time of the whole source update and of its parts,
// and of OpalCore's buildVolume (the programs' path, no VTK); then the same
// volume of 2000 Voronoi grains (docs/design.md §2.9).
#include "OpalDomainLayout.h"
#include "OpalModelParameters.h"
#include "OpalVolumeBuild.h"
#include "vtkOpalSource.h"

#include "vtkNew.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace
{
template <typename F>
double bestSeconds(int repeats, F&& work)
{
  double best = 1e300;
  for (int r = 0; r < repeats; ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    work();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}
} // namespace

int main()
{
  const int repeats = 5;
  const opal::ModelParameters parameters;
  const double layoutSeconds = bestSeconds(repeats, [&] { opal::DomainLayout::build(parameters); });

  int seed = 1;
  const double volumeSeconds = bestSeconds(repeats, [&] {
    vtkNew<vtkOpalSource> source;
    source->SetSeed(seed++);
    source->Update();
  });
  const double builtSeconds = bestSeconds(repeats, [&] { opal::buildVolume(parameters); });
  std::printf("opal volume 160x80x200, 250 domains, %u hardware threads, best of %d\n",
    std::thread::hardware_concurrency(), repeats);
  std::printf("  domain layout      %.4f s\n", layoutSeconds);
  std::printf("  whole volume       %.4f s   (vtkOpalSource; goal <= 0.15 s on 2 cores)\n", volumeSeconds);
  std::printf("  whole volume       %.4f s   (OpalCore's buildVolume, as opal-render)\n", builtSeconds);

  opal::ModelParameters grains;
  grains.DomainLayout = opal::DomainLayoutKind::Voronoi;
  grains.VoronoiCellCount = 2000;
  const double grainLayoutSeconds = bestSeconds(repeats, [&] { opal::DomainLayout::build(grains); });
  const double grainVolumeSeconds = bestSeconds(repeats, [&] {
    vtkNew<vtkOpalSource> source;
    source->SetModelParameters(grains);
    source->SetSeed(seed++);
    source->Update();
  });
  std::printf("voronoi layout, 2000 cells, same grid\n");
  std::printf("  cells and clusters %.4f s\n", grainLayoutSeconds);
  std::printf("  whole volume       %.4f s   (vtkOpalSource; goal <= 0.5 s on 2 cores)\n", grainVolumeSeconds);
  return 0;
}
