#include "vtkSMOpalPipelineWalk.h"

#include "vtkSMInputProperty.h"
#include "vtkSMProxy.h"

#include <algorithm>
#include <cstring>

namespace vtkSMOpalPipelineWalk
{
vtkSMProxy* UpstreamOpalVolume(vtkSMProxy* proxy)
{
  // A pipeline deeper than this is not one a user builds on purpose.
  constexpr int MaximumDepth = 16;
  for (int depth = 0; proxy && depth < MaximumDepth; ++depth)
  {
    if (proxy->GetXMLName() && std::strcmp(proxy->GetXMLName(), "OpalVolume") == 0)
    {
      return proxy;
    }
    auto* input = vtkSMInputProperty::SafeDownCast(proxy->GetProperty("Input"));
    proxy = input && input->GetNumberOfProxies() > 0 ? input->GetProxy(0) : nullptr;
  }
  return nullptr;
}

std::vector<vtkSMProxy*> DownstreamProxies(vtkSMProxy* proxy)
{
  std::vector<vtkSMProxy*> found;
  std::vector<vtkSMProxy*> queue{ proxy };
  for (std::size_t next = 0; next < queue.size(); ++next)
  {
    vtkSMProxy* current = queue[next];
    for (unsigned int i = 0; i < current->GetNumberOfConsumers(); ++i)
    {
      vtkSMProxy* consumer = current->GetConsumerProxy(i);
      // Representations are source proxies too; the pipeline's are in "filters".
      const char* group = consumer ? consumer->GetXMLGroup() : nullptr;
      const bool isFilter = group && std::strcmp(group, "filters") == 0;
      if (isFilter && consumer != proxy && std::find(found.begin(), found.end(), consumer) == found.end())
      {
        found.push_back(consumer);
        queue.push_back(consumer);
      }
    }
  }
  return found;
}
} // namespace vtkSMOpalPipelineWalk
