// The SPIR-V of the render passes, compiled by glslangValidator from shaders/
// at build time and embedded into the library (cmake/OpalEmbed.cmake).
#pragma once

#include <cstddef>
#include <cstdint>

namespace opal::embedded
{

struct Spirv
{
  const std::uint32_t* Words;
  std::size_t WordCount;
};

Spirv lightOpticalDepthShader();
Spirv viewMarchShader();
Spirv specularHighlightShader();
Spirv spectrumToColourShader();
Spirv braggShadowTableShader();
// The passes that read per-voxel fields, compiled with OPAL_VOLUME_ADDRESSES.
Spirv lightOpticalDepthAddressedShader();
Spirv viewMarchAddressedShader();
Spirv specularHighlightAddressedShader();

} // namespace opal::embedded
