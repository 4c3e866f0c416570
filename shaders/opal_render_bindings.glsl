// What every pass declares alike: the contract, the parameter block and the
// wavelength table (opal_render_contract.h; docs/design.md §3.8).
#include "opal_render_contract.h"

layout(std140, set = 0, binding = ParametersBinding) uniform ParameterBlock { RenderParameterBlock P; };
layout(std430, set = 0, binding = WavelengthTableBinding) readonly buffer WavelengthTable { WavelengthBinRecord bins[]; };
