// Data compiled into the library at build time: the SPIR-V of the shaders
// (compiled by glslangValidator from shaders/) and the CIE tables (data/).
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
Spirv spectrumToColourShader();

// CSV text of the CIE 1931 2-degree colour-matching functions (1 nm) and of D65 (5 nm).
const char* cie1931Xyz2DegreeCsv();
const char* cieD65Csv();

} // namespace opal::embedded
