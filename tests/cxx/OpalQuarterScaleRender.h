// The render filter over the volume source at a quarter of the paper's
// voxels (80 x 40 x 100): the VTK pipeline the filter-level tests drive
// (abort, background frames).
#pragma once

#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkNew.h"

namespace opaltest
{

struct QuarterScaleRender
{
  vtkNew<vtkOpalSource> Source;
  vtkNew<vtkOpalSpectralRender> Render;

  // The render of width x height pixels, connected to the source.
  QuarterScaleRender(int width, int height)
  {
    this->Source->SetDimensions(80, 40, 100);
    this->Render->SetInputConnection(this->Source->GetOutputPort(0));
    this->Render->SetImageSize(width, height);
  }
};

} // namespace opaltest
