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
#include "vtkXMLPImageDataWriter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

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

void showProgress(vtkAlgorithm* algorithm, ProgressBar& bar, int pieces)
{
  // The algorithm reports 0 to 1 for each piece; the bar shows the whole.
  struct Pieces
  {
    ProgressBar* Bar;
    int Count, Done;
  };
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(new Pieces{ &bar, std::max(pieces, 1), 0 });
  command->SetClientDataDeleteCallback([](void* client) { delete static_cast<Pieces*>(client); });
  command->SetCallback([](vtkObject*, unsigned long event, void* client, void* callData) {
    auto* p = static_cast<Pieces*>(client);
    if (event == vtkCommand::EndEvent)
    {
      ++p->Done;
      return;
    }
    p->Bar->show((p->Done + *static_cast<double*>(callData)) / p->Count);
  });
  algorithm->AddObserver(vtkCommand::ProgressEvent, command);
  algorithm->AddObserver(vtkCommand::EndEvent, command);
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

namespace
{
// A folder created exclusively under an unpredictable name, removed with
// what is left in it when the holder ends.
class StagingFolder
{
public:
  explicit StagingFolder(const std::filesystem::path& beside)
  {
    const std::filesystem::path folder = beside.parent_path().empty() ? "." : beside.parent_path();
    std::string pattern = (folder / ("." + beside.filename().string() + "-XXXXXX")).string();
    if (mkdtemp(pattern.data()))
    {
      this->Path = pattern;
    }
    else
    {
      this->Error = std::strerror(errno);
    }
  }
  ~StagingFolder()
  {
    std::error_code ignored;
    std::filesystem::remove_all(this->Path, ignored);
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  std::filesystem::path Path;
  std::string Error;
};

// The Source of each <Piece> element of a summary's text (VTK writes
// `<Piece Extent="..." Source="name"/>`), where it is a plain name (no '/').
std::vector<std::string> pieceSources(const std::string& text)
{
  const auto wordChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
  const std::string tag = "<Piece", key = "Source=\"";
  std::vector<std::string> sources;
  for (std::size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1))
  {
    const std::size_t end = std::min(text.find('>', at), text.size());
    std::size_t source = text.find(key, at);
    while (source < end && wordChar(text[source - 1])) // a longer name ending in Source
    {
      source = text.find(key, source + 1);
    }
    const std::size_t first = source + key.size();
    const std::size_t last = source < end ? text.find('"', first) : std::string::npos;
    const bool pieceTag = at + tag.size() >= text.size() || !wordChar(text[at + tag.size()]); // not <PieceX
    if (!pieceTag || last == std::string::npos || last == first)
    {
      continue;
    }
    const std::string name = text.substr(first, last - first);
    if (name.find('/') == std::string::npos)
    {
      sources.push_back(name);
    }
  }
  return sources;
}

// The piece files an earlier summary at `summary` names that the new set
// does not write again (an earlier run with more pieces), so that they go
// with it: only plain names beside it (a summary cannot name a file
// elsewhere) of regular files.
std::vector<std::filesystem::path> stalePieces(
  const std::filesystem::path& summary, const std::vector<std::filesystem::path>& written)
{
  std::ifstream in(summary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::filesystem::path> stale;
  for (const std::string& name : pieceSources(text))
  {
    const std::filesystem::path piece = summary.parent_path() / name;
    std::error_code error;
    const bool regular = std::filesystem::is_regular_file(std::filesystem::symlink_status(piece, error));
    if (regular && name != "." && name != ".." &&
      std::find(written.begin(), written.end(), piece) == written.end() &&
      std::find(stale.begin(), stale.end(), piece) == stale.end())
    {
      stale.push_back(piece);
    }
  }
  return stale;
}
} // namespace

std::string writePartitionedImageDataFile(const std::string& path, vtkAlgorithm* source, int pieces)
{
  const std::filesystem::path target(path);
  const StagingFolder staging(target);
  if (staging.Path.empty())
  {
    return "could not write " + path + ": " + staging.Error + " (creating a folder for its pieces beside it)";
  }
  // Signals are not held while the pieces are built (an abort would make
  // VTK's partitioned writer ask for the piece again, endlessly): a kill then
  // leaves the hidden staging folder, never a target touched.
  vtkNew<vtkXMLPImageDataWriter> writer;
  writer->SetInputConnection(source->GetOutputPort());
  writer->SetFileName((staging.Path / target.filename()).c_str());
  writer->SetNumberOfPieces(pieces);
  writer->SetStartPiece(0);
  writer->SetEndPiece(pieces - 1);
  writer->SetDataModeToBinary(); // as writeImageDataFile, for bookworm's expat
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1)
  {
    return "could not write " + path + " (the volume or one of its " + std::to_string(pieces) + " pieces failed)";
  }
  // The summary and its pieces, under the names the writer gave them.
  std::vector<std::filesystem::path> staged, targets;
  std::error_code listing;
  for (const auto& entry : std::filesystem::directory_iterator(staging.Path, listing))
  {
    staged.push_back(entry.path());
    targets.push_back(target.parent_path() / entry.path().filename());
  }
  if (listing)
  {
    return "could not write " + path + ": " + listing.message() + " (listing its pieces)";
  }
  // An earlier set's pieces beyond the new ones go with it (kept if it fails).
  const std::vector<std::filesystem::path> stale = stalePieces(target, targets);
  std::vector<std::filesystem::path> replaced = targets;
  replaced.insert(replaced.end(), stale.begin(), stale.end());
  const SignalsHeld held; // delivered once the set is whole or gone
  FileSetTransaction transaction(replaced);
  for (std::size_t i = 0; i < staged.size(); ++i)
  {
    const std::string error = moveFileAtomically(staged[i], targets[i]);
    if (!error.empty())
    {
      return error;
    }
  }
  for (const std::filesystem::path& piece : stale)
  {
    std::error_code error;
    if (!std::filesystem::remove(piece, error) && error)
    {
      return "could not remove " + piece.string() + ", a piece of the earlier " + path + ": " + error.message();
    }
  }
  transaction.commit();
  return {};
}
