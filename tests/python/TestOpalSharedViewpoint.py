"""pvpython: the render's preset settings and one light and eye per stone
(docs/design.md §2.8, §4).

- A render connected to an Opal Volume shows the preset's ImageSize and
  placement (ModelRotation; fig13: 5 degrees about x) in its properties, filled
  in again when the volume's preset changes; an edit afterwards is used; the
  filled-in turn gives the same image as the volume's placement applied at
  render time (so it is not applied twice).
- A Bragg map of the same volume takes the render's light, eye, rotation and
  refractive index and stays linked with it both ways.
- The Bragg map's ModelRotation turns the light and eye back into the stone's
  frame: its map equals one without rotation and the light turned by R^-1.
- Deleting the render leaves the map working, unlinked."""
import math

import numpy
from paraview import servermanager as sm
from paraview.simple import Delete, LoadPlugin, OutputPort
from vtkmodules.util.numpy_support import vtk_to_numpy

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
small = dict(Dimensions=[40, 20, 50], DomainCount=30)

volume = OpalVolume(Preset="fig13", **small)  # noqa: F821 (from the plugin)
render = OpalSpectralRender(Input=volume)  # noqa: F821
check(list(render.ImageSize) == [640, 480], f"fig13's image size is shown: {list(render.ImageSize)}")
check(list(render.ModelRotation) == [5, 0, 0], f"fig13's placement is shown: {list(render.ModelRotation)}")
check(render.PresetPlacement == 0, "the placement is not applied a second time")
volume.Preset = "fig15"
check(list(render.ImageSize) == [300, 300] and list(render.ModelRotation) == [0, 0, 0],
      f"choosing fig15 on the volume fills in its size and placement: {list(render.ImageSize)}, "
      f"{list(render.ModelRotation)}")
volume.Preset = "black-opal"
check(render.BraggModel == "coupled-wave" and render.LatticePlanes == "fcc",
      f"choosing black-opal fills in its Bragg model and planes: {render.BraggModel}, {render.LatticePlanes}")
volume.Preset = "fig13"
check(render.BraggModel == "paper" and render.LatticePlanes == "111", "fig13 the paper's Bragg model")
volume.DomainCount = 30  # a preset sets the model's 250 (docs/design.md §2.8): small again
render.ImageSize = [64, 48]
render.UpdatePipeline()
image = sm.Fetch(render)
check(image.GetDimensions()[:2] == (64, 48), f"an edited size is used: {image.GetDimensions()}")

# The filled-in turn equals the volume's placement applied at render time.
at_render_time = OpalSpectralRender(Input=volume, ImageSize=[64, 48])  # noqa: F821
at_render_time.ModelRotation = [0, 0, 0]
at_render_time.PresetPlacement = 1
at_render_time.UpdatePipeline()
rgb = vtk_to_numpy(image.GetPointData().GetArray("Radiance"))
reference = vtk_to_numpy(sm.Fetch(at_render_time).GetPointData().GetArray("Radiance"))
check(numpy.array_equal(rgb, reference), "ModelRotation 5 0 0 without placement = placement at render time")

bragg = OpalBraggMap(Input=OutputPort(volume, 1))  # noqa: F821
for name in ("LightPosition", "EyePosition", "ModelRotation", "RefractiveIndex"):
    mine, theirs = bragg.GetProperty(name), render.GetProperty(name)
    check([mine[i] for i in range(len(mine))] == [theirs[i] for i in range(len(theirs))],
          f"the Bragg map's {name} is the render's")
render.LightPosition = [10, 50, 5]
check(list(bragg.LightPosition) == [10, 50, 5], f"moving the render's light moves the map's: {list(bragg.LightPosition)}")
bragg.EyePosition = [0, 55, 20]
check(list(render.EyePosition) == [0, 55, 20], f"moving the map's eye moves the render's: {list(render.EyePosition)}")
check(list(bragg.ModelRotation) == [5, 0, 0], "the map shows fig13's placement too")


def wavelengths(map_proxy):
    map_proxy.UpdatePipeline()
    return vtk_to_numpy(sm.Fetch(map_proxy).GetCellData().GetArray("BraggWavelength"))


# R = Rx(5 degrees); the light in the stone's frame is R^T L.
a = math.radians(5.0)
rotation = numpy.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
plain_volume = OpalVolume(Preset="custom", DomainDiameterRange=[250, 350], **small)  # noqa: F821
plain = OpalBraggMap(Input=OutputPort(plain_volume, 1))  # noqa: F821
plain.ModelRotation = [0, 0, 0]
plain.LightPosition = list(rotation.T @ numpy.array([10.0, 50.0, 5.0]))
check(numpy.allclose(wavelengths(bragg), wavelengths(plain), rtol=1e-9, atol=1e-6),
      "ModelRotation 5 0 0 = the light turned back by R^-1")

# Deleting the render unlinks the map (a link to a deleted proxy would crash).
Delete(at_render_time)
Delete(render)
bragg.LightPosition = [0, 58, 0]
check(wavelengths(bragg).size > 0, "the map renders on after its render is deleted")
finish("TestOpalSharedViewpoint")
