#include "OpalCliSupport.h"

#include "OpalAtomicFile.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkXMLImageDataWriter.h"

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
  void DisplayText(const char* text) override { std::cerr << text; }
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

void installStderrOutputWindow()
{
  vtkNew<StderrOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
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
