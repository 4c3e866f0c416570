// Memory estimates, so requests that cannot fit are refused up front with a
// message that states the estimate, instead of failing half way.
#pragma once

#include <cstdint>
#include <string>

namespace opal
{

// Physical memory of this machine in bytes (0 if unknown).
std::uint64_t physicalMemoryBytes();

// "2.4 GB", "310 MB": bytes for messages.
std::string formatBytes(std::uint64_t bytes);

// Bytes per voxel of the volume's point arrays (docs/design.md §2.5 fields).
constexpr std::uint64_t VolumeBytesPerVoxel = 1 + 4 + 12 + 4 + 4 + 4 + 4 + 4 + 16; // LatticeOrientation last
// What a build for the render keeps (VolumeArrays::Render): DomainId,
// ScatteringCoefficient, SurfaceDistance.
constexpr std::uint64_t RenderVolumeBytesPerVoxel = 4 + 4 + 4;

} // namespace opal
