// Every polygon preset (docs/design.md §2.8, §2.11) places all its domains (250
// unless it sets DomainCount) at paper scale (the Voronoi presets are TestOpalVoronoiGrains'),
// with the preset's sphere diameters, and the domain polygons match.
#include "OpalTestVolumes.h"

#include "OpalModelFields.h"
#include "OpalPresets.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <string>

int TestOpalPresetDomains(int, char*[])
{
  // Every value a preset sets names a field of the table (OpalModelFields.h),
  // with as many values as the field has, and applying the preset sets it.
  for (const opal::PresetSettings& preset : opal::presets())
  {
    opal::ModelParameters applied;
    applied.applyPreset(opal::presetIndexByName(preset.Name));
    for (const opal::PresetValue& value : preset.Model)
    {
      const opal::ModelField* field = opal::presetModelField(value.Property);
      OPAL_CHECK(field != nullptr, std::string(preset.Name) + " sets a known field, " + value.Property);
      OPAL_CHECK(field && field->Get(applied) == value.Values,
        std::string(preset.Name) + " sets " + value.Property + " to its values");
    }
  }
  for (const opal::PresetSettings& preset : opal::presets())
  {
    if (preset.valuesOf("DomainLayout"))
    {
      continue;
    }
    const std::string name = preset.Name;
    const std::vector<double>& diameterRange = *preset.valuesOf("DomainDiameterRange");
    const int count = preset.valuesOf("DomainCount") ? static_cast<int>(preset.valuesOf("DomainCount")->at(0)) : 250;
    const std::string counted = std::to_string(count);
    vtkNew<vtkOpalSource> source;
    OPAL_CHECK(source->SetPresetByName(preset.Name), name + " is a known preset");
    OPAL_CHECK(source->GetExecutive()->Update() == 1, name + " builds");
    vtkImageData* volume = source->GetOutput(0);
    vtkPolyData* polygons = vtkPolyData::SafeDownCast(source->GetOutputDataObject(1));
    const double placed = volume->GetFieldData()->GetArray("DomainsPlaced")->GetComponent(0, 0);
    OPAL_CHECK(placed == count, name + " places all " + counted + " domains, got " + std::to_string(placed));
    OPAL_CHECK(polygons && polygons->GetNumberOfCells() == count, name + " has " + counted + " domain polygons");
    vtkDataArray* cellDiameter = polygons->GetCellData()->GetArray("ParticleDiameter");
    for (const char* array : { "DomainId", "ParticleDiameter", "Normal", "BraggLambdaMax" })
    {
      OPAL_CHECK(polygons->GetCellData()->GetArray(array) != nullptr, name + " polygons carry " + array);
    }
    bool inRange = true;
    for (vtkIdType c = 0; cellDiameter && c < cellDiameter->GetNumberOfTuples(); ++c)
    {
      const double l = cellDiameter->GetComponent(c, 0);
      inRange = inRange && l >= diameterRange[0] - 1e-3 && l <= diameterRange[1] + 1e-3;
    }
    OPAL_CHECK(inRange, name + " domain diameters within the preset's range");
    // Every polygon's domain has voxels in the volume.
    vtkDataArray* ids = volume->GetPointData()->GetArray("DomainId");
    std::vector<int> voxelsPerDomain(static_cast<std::size_t>(count), 0);
    for (vtkIdType id = 0; id < ids->GetNumberOfTuples(); ++id)
    {
      const int d = static_cast<int>(ids->GetComponent(id, 0));
      if (d >= 0 && d < count)
      {
        ++voxelsPerDomain[static_cast<std::size_t>(d)];
      }
    }
    bool allHaveVoxels = true;
    for (int v : voxelsPerDomain)
    {
      allHaveVoxels = allHaveVoxels && v > 0;
    }
    OPAL_CHECK(allHaveVoxels, name + " every domain owns voxels");
  }
  return opaltest::finish("TestOpalPresetDomains");
}
