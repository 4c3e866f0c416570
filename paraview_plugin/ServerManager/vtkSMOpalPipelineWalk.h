// Walks ParaView's pipeline of proxies from an Opal filter up to its Opal
// Volume and from the volume down to the filters that use it (through other
// filters too), so a preset and a light can reach every view of one stone.
#pragma once

#include <vector>

class vtkSMProxy;

namespace vtkSMOpalPipelineWalk
{
/// The Opal Volume proxy this proxy's first inputs lead up to, or nullptr.
vtkSMProxy* UpstreamOpalVolume(vtkSMProxy* proxy);

/// The source and filter proxies downstream of `proxy` (not representations
/// or views), each once, nearest first.
std::vector<vtkSMProxy*> DownstreamProxies(vtkSMProxy* proxy);
} // namespace vtkSMOpalPipelineWalk
