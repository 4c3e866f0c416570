// What the programs need of VTK: its messages on stderr, an algorithm's
// progress on a bar, writing .vti files. opal-volume links it; opal-render
// loads it (through its .vti output module) only when a .vti is asked for.
#pragma once

#include "OpalCliSupport.h"

#include <string>

class vtkAlgorithm;
class vtkImageData;

// Routes VTK's errors and warnings to stderr as one plain line each,
// prefixed with the program's name; the executive's request dumps are dropped.
void installStderrOutputWindow(const std::string& program);

// Shows `algorithm`'s progress on `bar` (which must outlive the algorithm's updates).
void showProgress(vtkAlgorithm* algorithm, ProgressBar& bar);

// Writes image data as a .vti (inline binary, zlib); empty string on success, else the reason.
std::string writeImageDataFile(const std::string& path, vtkImageData* image);
