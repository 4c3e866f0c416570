#include "OpalVtkSupport.h"

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
#include <iostream>

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

} // namespace

void installStderrOutputWindow(const std::string& program)
{
  vtkNew<StderrOutputWindow> window;
  window->Program = program;
  vtkOutputWindow::SetInstance(window);
  // ParaView's VTK also logs every error to stderr itself, with file and line.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

void showProgress(vtkAlgorithm* algorithm, ProgressBar& bar)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback([](vtkObject*, unsigned long, void* client, void* callData) {
    static_cast<ProgressBar*>(client)->show(*static_cast<double*>(callData));
  });
  command->SetClientData(&bar);
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
