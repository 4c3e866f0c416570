// A minimal harness for the C++ tests: checks that count failures and print
// what went wrong, and a recorder of the errors and warnings VTK objects emit.
#pragma once

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"

#include <chrono>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace opaltest
{
// The message of the exception `call` throws, "" where it throws none.
inline std::string thrown(const std::function<void()>& call)
{
  try
  {
    call();
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}


inline int& failureCount()
{
  static int failures = 0;
  return failures;
}

inline void check(bool condition, const std::string& what, const char* file, int line)
{
  if (!condition)
  {
    ++failureCount();
    std::cerr << file << ":" << line << ": FAILED: " << what << std::endl;
  }
}

inline int finish(const char* testName)
{
  if (failureCount() == 0)
  {
    std::cout << testName << ": all checks passed" << std::endl;
    return EXIT_SUCCESS;
  }
  std::cerr << testName << ": " << failureCount() << " check(s) failed" << std::endl;
  return EXIT_FAILURE;
}

// For tests that provoke errors on purpose and check them with a
// MessageRecorder: VTK's output window and its logger stay quiet (ctest
// fails a VTK test whose output shows an error line).
inline void silenceExpectedErrors()
{
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

// Collects the ErrorEvent and WarningEvent messages of an object instead of printing them.
class MessageRecorder : public vtkCommand
{
public:
  static MessageRecorder* New() { return new MessageRecorder; }
  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string text = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(text);
  }
  void watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }
  void clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
  bool anyContains(const std::vector<std::string>& messages, const std::string& needle) const
  {
    for (const auto& message : messages)
    {
      if (message.find(needle) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

// One invalid input for a bad-input test: how to break the algorithm and the
// text its error message must contain (the parameter's name).
template <typename Algorithm>
struct BadCase
{
  std::string Description;
  std::function<void(Algorithm*)> Break;
  std::string Expected;
};

// Aborts an algorithm, as ParaView's stop button does, once its progress
// reaches AbortAt; remembers when.
class AbortOnProgress : public vtkCommand
{
public:
  static AbortOnProgress* New() { return new AbortOnProgress; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    if (!this->Aborted && *static_cast<double*>(callData) >= this->AbortAt)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      this->Aborted = true;
      this->When = std::chrono::steady_clock::now();
    }
  }
  double secondsSinceAbort() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->When).count();
  }
  double AbortAt = 0.3;
  bool Aborted = false;
  std::chrono::steady_clock::time_point When;
};

} // namespace opaltest

#define OPAL_CHECK(condition, what) ::opaltest::check((condition), (what), __FILE__, __LINE__)
