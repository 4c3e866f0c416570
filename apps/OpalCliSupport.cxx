#include "OpalCliSupport.h"

#include "OpalAtomicFile.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace
{
class StderrOutputWindow : public vtkOutputWindow
{
public:
  static StderrOutputWindow* New();
  vtkTypeMacro(StderrOutputWindow, vtkOutputWindow);
  std::string Program;

  // VTK formats "ERROR: In file, line N\nclass (0x...): message\n\n"; keep the message.
  void DisplayText(const char* text) override
  {
    std::string message(text ? text : "");
    if (message.find("returned failure for request") != std::string::npos)
    {
      return; // the executive's echo of an error already shown
    }
    const std::size_t objectEnd = message.find("): ");
    if (objectEnd != std::string::npos)
    {
      message = message.substr(objectEnd + 3);
    }
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    std::replace(message.begin(), message.end(), '\n', ' ');
    if (!message.empty())
    {
      std::cerr << this->Program << ": " << message << std::endl;
    }
  }
};
vtkStandardNewMacro(StderrOutputWindow);

void drawProgress(vtkObject* caller, unsigned long, void* label, void* callData)
{
  const double fraction = *static_cast<double*>(callData);
  constexpr int Width = 40;
  const int filled = static_cast<int>(fraction * Width + 0.5);
  std::fprintf(stderr, "\r%-10s [%s%s] %3d%%", static_cast<std::string*>(label)->c_str(),
    std::string(static_cast<std::size_t>(filled), '#').c_str(),
    std::string(static_cast<std::size_t>(Width - filled), ' ').c_str(), static_cast<int>(fraction * 100 + 0.5));
  if (fraction >= 1.0)
  {
    std::fprintf(stderr, "\n");
  }
  std::fflush(stderr);
  (void)caller;
}
} // namespace

void installStderrOutputWindow(const std::string& program)
{
  vtkNew<StderrOutputWindow> window;
  window->Program = program;
  vtkOutputWindow::SetInstance(window);
  // ParaView's VTK also logs every error to stderr itself, with file and line.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

std::string oneLineFailure(const std::string& program, const std::string& what)
{
  return program + ": " + what + " (see --help)\n";
}

void showProgress(vtkAlgorithm* algorithm, const std::string& label)
{
  if (!::isatty(STDERR_FILENO))
  {
    return;
  }
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback(drawProgress);
  command->SetClientData(new std::string(label));
  command->SetClientDataDeleteCallback([](void* data) { delete static_cast<std::string*>(data); });
  algorithm->AddObserver(vtkCommand::ProgressEvent, command);
}

std::string writeImageDataFile(const std::string& path, vtkImageData* image)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  // Inline binary, not appended: Debian bookworm's VTK 9.2 with its patched
  // expat cannot read appended XML data back ("junk after document element").
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  return writeFileAtomically(path, [&](const std::string& temporary) {
    writer->SetFileName(temporary.c_str());
    return writer->Write() == 1;
  });
}
