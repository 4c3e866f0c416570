"""pvpython: the plugin loads, its Opal Volume proxy is documented and builds
every paper preset with the arrays of docs/design.md §2.5 and all 250 domains,
and the Voronoi presets (harlequin, pinfire) with CellId, their ordered cells
as domains and the cells' faces on the Domains output."""

from paraview import servermanager as sm
from paraview.simple import LoadPlugin

import opal_test_config as config
from opal_test_support import check, finish

# Defines the plugin's constructors (OpalVolume, ...) in this module's namespace.
LoadPlugin(config.PLUGIN, remote=False, ns=globals())

ARRAYS = {
    "VoxelType": "vtkUnsignedCharArray",
    "ParticleDiameter": "vtkFloatArray",
    "Normal": "vtkFloatArray",
    "DomainId": "vtkIntArray",
    "BraggLambdaMax": "vtkFloatArray",
    "BraggLambdaMin": "vtkFloatArray",
    "ScatteringCoefficient": "vtkFloatArray",
    "SurfaceDistance": "vtkFloatArray",
    "LatticeOrientation": "vtkFloatArray",
}


volume = OpalVolume()
for name in volume.ListProperties():
    documentation = volume.GetProperty(name).SMProperty.GetDocumentation()
    check(documentation is not None and documentation.GetDescription().strip(),
          f"property {name} has documentation")

for preset in ["fig10", "fig11", "fig12", "fig13", "fig15", "fig17"]:
    volume = OpalVolume(Preset=preset)
    volume.UpdatePipeline()
    data = sm.Fetch(volume)
    check(data.GetDimensions() == (160, 80, 200), f"{preset}: paper-scale grid")
    for name, class_name in ARRAYS.items():
        array = data.GetPointData().GetArray(name)
        check(array is not None and array.GetClassName() == class_name,
              f"{preset}: {name} is a {class_name}")
    placed = data.GetFieldData().GetArray("DomainsPlaced").GetValue(0)
    check(placed == 250, f"{preset}: 250 domains placed, got {placed}")
    check(data.GetFieldData().GetAbstractArray("Preset").GetValue(0) == preset,
          f"{preset}: field data records the preset")
    polygons = sm.Fetch(volume, idx=1)
    check(polygons.GetNumberOfCells() == 250, f"{preset}: 250 domain polygons")

for preset, cells, fraction in [("harlequin", 150, 0.5), ("pinfire", 3000, 0.12)]:
    volume = OpalVolume(Preset=preset)
    volume.UpdatePipeline()
    data = sm.Fetch(volume)
    cell_ids = data.GetPointData().GetArray("CellId")
    check(cell_ids is not None and cell_ids.GetClassName() == "vtkIntArray", f"{preset}: CellId is a vtkIntArray")
    fields = data.GetFieldData()
    check(fields.GetArray("DomainLayout").GetValue(0) == 1, f"{preset}: the layout is voronoi")
    check(fields.GetArray("VoronoiCellCount").GetValue(0) == cells, f"{preset}: {cells} cells")
    placed = fields.GetArray("DomainsPlaced").GetValue(0)
    check(abs(placed - fraction * cells) <= 0.05 * cells,
          f"{preset}: about {fraction:.0%} of {cells} cells ordered, got {placed}")
    faces = sm.Fetch(volume, idx=1)
    check(faces.GetNumberOfCells() > placed, f"{preset}: the ordered cells' faces on the Domains output")

finish("TestOpalPluginPresets")
