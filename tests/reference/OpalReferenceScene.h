// The reference renderer's scene from an Opal volume (vtkImageData with the
// docs/design.md §2.5 arrays, absorption's where present), for the oracle test and the speed bench. The domain
// table is rebuilt from the voxels: each domain's lattice normal and its FCC
// (111) plane spacing d = sqrt(2/3) l (eq. 3).
#pragma once

#include "OpalReferenceRenderer.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <cmath>

namespace opalreference
{

inline Scene sceneFromVolume(vtkImageData* volume)
{
  Scene scene;
  int dims[3];
  volume->GetDimensions(dims);
  for (int a = 0; a < 3; ++a)
  {
    scene.Dimensions[static_cast<std::size_t>(a)] = dims[a];
    scene.Origin[static_cast<std::size_t>(a)] = volume->GetOrigin()[a];
    scene.Spacing[static_cast<std::size_t>(a)] = volume->GetSpacing()[a];
  }
  vtkPointData* pd = volume->GetPointData();
  vtkDataArray* scattering = pd->GetArray("ScatteringCoefficient");
  vtkDataArray* distance = pd->GetArray("SurfaceDistance");
  vtkDataArray* ids = pd->GetArray("DomainId");
  vtkDataArray* normals = pd->GetArray("Normal");
  vtkDataArray* diameters = pd->GetArray("ParticleDiameter");
  vtkDataArray* absorption = pd->GetArray("AbsorptionCoefficient");
  vtkDataArray* exponent = pd->GetArray("AbsorptionExponent");
  for (vtkIdType i = 0; i < volume->GetNumberOfPoints(); ++i)
  {
    if (absorption && exponent)
    {
      scene.Absorption.push_back(static_cast<float>(absorption->GetComponent(i, 0)));
      scene.AbsorptionExponent.push_back(static_cast<float>(exponent->GetComponent(i, 0)));
    }
    scene.Scattering.push_back(static_cast<float>(scattering->GetComponent(i, 0)));
    scene.SurfaceDistance.push_back(static_cast<float>(distance->GetComponent(i, 0)));
    const int id = static_cast<int>(ids->GetComponent(i, 0));
    scene.DomainId.push_back(id);
    if (id < 0)
    {
      continue;
    }
    if (scene.Domains.size() <= static_cast<std::size_t>(id))
    {
      scene.Domains.resize(static_cast<std::size_t>(id) + 1, { 0, 0, 0, 0 });
    }
    double n[3];
    normals->GetTuple(i, n);
    scene.Domains[static_cast<std::size_t>(id)] = { n[0], n[1], n[2],
      std::sqrt(2.0 / 3.0) * diameters->GetComponent(i, 0) };
  }
  return scene;
}

} // namespace opalreference
