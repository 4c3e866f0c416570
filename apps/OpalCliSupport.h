// What the command-line programs share beyond their flags: VTK messages on
// stderr, a progress bar on a terminal, writing .vti files.
#pragma once

#include <string>

class vtkAlgorithm;
class vtkImageData;

// Routes VTK's errors and warnings to stderr as one plain line each,
// prefixed with the program's name; the executive's request dumps are dropped.
void installStderrOutputWindow(const std::string& program);

// CLI11's failure message as one line: "program: what went wrong (see --help)".
std::string oneLineFailure(const std::string& program, const std::string& what);

// Shows `algorithm`'s progress as a bar on stderr, labelled, if stderr is a terminal.
void showProgress(vtkAlgorithm* algorithm, const std::string& label);

// Writes image data as a .vti (inline binary, zlib); empty string on success, else the reason.
std::string writeImageDataFile(const std::string& path, vtkImageData* image);
