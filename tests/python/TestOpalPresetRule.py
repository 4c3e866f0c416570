"""pvpython: one preset rule for ParaView, pvpython and the command line
(docs/design.md §2.8): choosing a preset fills in the values it sets (read
back from the proxy, as the panel shows them), a value edited afterwards is
used, and opal-volume with the same preset and override builds the same
volume, array for array."""
import os

import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import opal_test_config as config
from opal_test_support import check, finish, run

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
small = dict(Dimensions=[40, 20, 50], DomainCount=30)

volume = OpalVolume(**small)  # noqa: F821 (from the plugin)
check(list(volume.DomainDiameterRange) == [250, 350], f"fig12 (the default) shows 250-350: {volume.DomainDiameterRange}")
volume.Preset = "fig15"
check(list(volume.DomainDiameterRange) == [200, 235], f"choosing fig15 shows 200-235: {volume.DomainDiameterRange}")
volume.Preset = "harlequin"
check(volume.DomainLayout == "voronoi" and volume.VoronoiCellCount == 150 and volume.OrderedFraction == 0.5,
      "choosing harlequin shows its Voronoi layout, 150 cells, half ordered")
volume.Preset = "black-opal"
check(volume.BackingThickness == 4 and volume.BackingAbsorption == 5 and volume.ScatteringVolumeFraction == 0.04,
      "choosing black-opal shows its body and backing")
check(volume.DomainLayout == "polygons" and volume.VoronoiCellCount == 1000,
      "a preset sets the model's defaults for what it does not list: black-opal after harlequin has polygons")
volume.Preset = "custom"
check(volume.BackingThickness == 4 and volume.ScatteringVolumeFraction == 0.04, "choosing custom keeps the values shown")

edited = OpalVolume(Preset="fig15", **small)  # noqa: F821
edited.DomainDiameterRange = [400, 500]
edited.UpdatePipeline()
data = sm.Fetch(edited)
used = data.GetFieldData().GetArray("DomainDiameterRange")
check((used.GetValue(0), used.GetValue(1)) == (400, 500),
      "a range edited after choosing the preset is used (field data)")
lambdas = vtk_to_numpy(data.GetPointData().GetArray("BraggLambdaMax"))
diameters = lambdas[lambdas > 0] / (2 * 1.45 * numpy.sqrt(2.0 / 3.0))
check(diameters.size > 0 and diameters.min() >= 399.9 and diameters.max() <= 500.1,
      f"the domains' spheres lie in 400-500 nm ({diameters.min():.1f}-{diameters.max():.1f})")

# The command line: the same preset and override give the same volume.
path = os.path.join(config.OUTPUT_DIRECTORY, "preset_rule_cli.vti")
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
run([config.OPAL_VOLUME, "--preset", "fig15", "--domain-diameter-range", "400", "500", "--dimensions", "40", "20",
     "50", "--domain-count", "30", "-o", path])
reader = vtkXMLImageDataReader()
reader.SetFileName(path)
reader.Update()
cli = reader.GetOutput()
for name in ("VoxelType", "ParticleDiameter", "DomainId", "BraggLambdaMax", "ScatteringCoefficient"):
    a = vtk_to_numpy(cli.GetPointData().GetArray(name))
    b = vtk_to_numpy(data.GetPointData().GetArray(name))
    check(a.shape == b.shape and numpy.array_equal(a, b), f"{name}: opal-volume and pvpython agree")
finish("TestOpalPresetRule")
