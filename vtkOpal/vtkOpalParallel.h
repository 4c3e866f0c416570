// Parallel loops for the Opal filters. Debian's ParaView builds VTK with the
// Sequential SMP backend as default and STDThread as an option; unless the
// user picked a backend (VTK_SMP_BACKEND_IN_USE), run on std::threads so
// filling the volume uses every core.
#pragma once

#include "vtkSMPTools.h"

#include <cstdlib>
#include <string>

namespace vtkOpalParallel
{
template <typename Functor>
void For(int begin, int end, Functor&& functor)
{
  const bool userChoseBackend = std::getenv("VTK_SMP_BACKEND_IN_USE") != nullptr;
  if (!userChoseBackend && std::string(vtkSMPTools::GetBackend()) == "Sequential")
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config(std::string("STDThread")),
      [&] { vtkSMPTools::For(begin, end, functor); });
  }
  else
  {
    vtkSMPTools::For(begin, end, functor);
  }
}
} // namespace vtkOpalParallel
