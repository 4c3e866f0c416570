// Counter-based random numbers: a value is a pure function of (seed, stream,
// counter), so any process computing any piece of the volume draws exactly the
// values the whole-volume run draws (docs/design.md §2.7).
#pragma once

#include <cstdint>

namespace opal
{

// SplitMix64's finaliser: a bijective 64-bit mixer with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The independent random streams of the model.
enum class RandomStream : std::uint64_t
{
  ScatteringDiameter = 1, // per voxel, counter = global voxel index
  DomainLayout = 2,       // sequential draws of the domain placement
  VoronoiCells = 3,       // sequential draws of the Voronoi sites, clusters and domains
  DiameterField = 4,      // per lattice node of the correlated diameter field
  LatticeSpin = 5,        // per domain, counter = domain id: the lattice's spin about its (111) normal
};

constexpr std::uint64_t hashCounter(std::uint64_t seed, RandomStream stream, std::uint64_t counter)
{
  return mix64(mix64(mix64(seed) ^ static_cast<std::uint64_t>(stream)) ^ counter);
}

// Uniform double in [0, 1) from the top 53 bits.
constexpr double unitFromHash(std::uint64_t h)
{
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

// A sequential generator over one stream; identical on every process.
class RandomSequence
{
public:
  RandomSequence(std::uint64_t seed, RandomStream stream)
    : Seed(seed)
    , Stream(stream)
  {
  }

  double uniform() { return unitFromHash(hashCounter(this->Seed, this->Stream, this->Counter++)); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * this->uniform(); }
  // Uniform integer in [lo, hi].
  int uniformInt(int lo, int hi)
  {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<int>(hashCounter(this->Seed, this->Stream, this->Counter++) % span);
  }

private:
  std::uint64_t Seed;
  RandomStream Stream;
  std::uint64_t Counter = 0;
};

} // namespace opal
