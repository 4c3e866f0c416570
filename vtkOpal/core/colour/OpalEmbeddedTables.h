// The official CIE tables (core/colour/data/), embedded into the library at build
// time (cmake/OpalEmbed.cmake), so no data file has to be found at run time.
#pragma once

namespace opal::embedded
{

// CSV text of the CIE 1931 2-degree colour-matching functions (1 nm) and of D65 (5 nm).
const char* cie1931Xyz2DegreeCsv();
const char* cieD65Csv();

} // namespace opal::embedded
