// What every pass declares alike: the contract, the parameter block and the
// wavelength table (opal_render_contract.h; docs/design.md §3.8).
#include "opal_render_contract.h"

layout(std140, set = 0, binding = ParametersBinding) uniform ParameterBlock { RenderParameterBlock P; };
layout(std430, set = 0, binding = WavelengthTableBinding) readonly buffer WavelengthTable { WavelengthBinRecord bins[]; };

// Dispatches within the device's workgroup count (docs/design.md §3.7): a
// one-dimensional pass of more groups than the device takes along x goes as
// a grid of rows of at most P.maxGroupsX groups, direct (ComputePipeline)
// or indirect (a queue's dispatchGrid). This invocation's item in the
// sequence, for a pass of `groupSize` invocations per workgroup along x.
int passItem(int groupSize)
{
  return int(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * groupSize + int(gl_LocalInvocationID.x);
}

// The grid (columns, rows) of an indirect dispatch of `groups` workgroups.
uvec2 dispatchGrid(uint groups)
{
  uint columns = uint(P.maxGroupsX);
  return uvec2(min(groups, columns), (groups + columns - 1u) / columns);
}
