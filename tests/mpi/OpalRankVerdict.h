// The verdict of a test run on every rank of an MPI job: it fails where any
// rank's checks failed, and rank 0 says so in the line ctest matches.
#pragma once

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <iostream>
#include <string>

namespace opaltest
{
// The job's exit status for `test` (0: every rank passed), said on rank 0.
inline int rankVerdict(vtkMultiProcessController* controller, bool passed, const std::string& test)
{
  int failures = passed ? 0 : 1, allFailures = 0;
  controller->AllReduce(&failures, &allFailures, 1, vtkCommunicator::SUM_OP);
  if (controller->GetLocalProcessId() == 0)
  {
    std::cout << test << " (" << controller->GetNumberOfProcesses() << " ranks): "
              << (allFailures == 0 ? "all checks passed" : "FAILED on " + std::to_string(allFailures) + " rank(s)")
              << std::endl;
  }
  return allFailures == 0 ? 0 : 1;
}
} // namespace opaltest
