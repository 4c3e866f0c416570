// What the programs need of VTK: its messages on stderr, an algorithm's
// progress on a bar, writing .vti and partitioned .pvti files. opal-volume links it; opal-render
// loads it (through its .vti output module) only when a .vti is asked for.
#pragma once

#include "OpalCliSupport.h"

#include <string>

class vtkAlgorithm;
class vtkImageData;

// Routes VTK's errors and warnings to stderr as one plain line each,
// prefixed with the program's name; the executive's request dumps are dropped.
void installStderrOutputWindow(const std::string& program);

// Shows `algorithm`'s progress on `bar` (which must outlive the algorithm's
// updates) over `pieces` executions, one per piece.
void showProgress(vtkAlgorithm* algorithm, ProgressBar& bar, int pieces = 1);

// Writes image data as a .vti (inline binary, zlib); empty string on success, else the reason.
std::string writeImageDataFile(const std::string& path, vtkImageData* image);

// Writes the image `source` produces as a partitioned .pvti at `path` and its
// `pieces` piece files beside it (NAME_0.vti, ...), each piece requested from
// the source alone (a source that fills only the extent asked, as
// vtkOpalSource does, then holds one piece at a time). The set is written in
// a private folder beside `path`, then moved into place all or none (renamed:
// the disk holds it once); the pieces of an earlier summary at `path` that
// the new set does not write again are removed with it. Empty string on
// success, else the reason.
std::string writePartitionedImageDataFile(const std::string& path, vtkAlgorithm* source, int pieces);
