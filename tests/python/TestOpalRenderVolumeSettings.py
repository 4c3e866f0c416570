"""pvpython: the render takes from its volume what opal-render takes from the
preset (docs/design.md §2.6, §2.8): on an Opal Volume its ImageSize and
ModelRotation show the preset's size and placement, and ModelRotation is the
whole turn; RefractiveIndex 0 takes the model's; a volume saved and read back
(no Opal Volume upstream: ImageSize 0 0 and the placement from its field data
at render time) renders the same image; values set on the filter are used as
set."""
import os

import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin, SaveData, XMLImageDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())


def radiance(render):
    image = sm.Fetch(render)
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetArray("Radiance")).copy()


small = dict(Dimensions=[40, 20, 50], DomainCount=30)
fig17 = OpalVolume(Preset="fig17", **small)  # noqa: F821 (from the plugin)
dims, _ = radiance(OpalSpectralRender(Input=fig17))  # noqa: F821
check(dims[:2] == (300, 300), f"fig17's render shows and renders its 300 x 300 (got {dims[:2]})")
dims, _ = radiance(OpalSpectralRender(Input=fig17, ImageSize=[40, 30]))  # noqa: F821
check(dims[:2] == (40, 30), f"a set ImageSize is used as set (got {dims[:2]})")

fig13 = OpalVolume(Preset="fig13", RefractiveIndex=1.5, **small)  # noqa: F821
fig12 = OpalVolume(Preset="fig12", RefractiveIndex=1.5, **small)  # noqa: F821
size = dict(ImageSize=[64, 48])
_, by_default = radiance(OpalSpectralRender(Input=fig13, **size))  # noqa: F821
_, explicit = radiance(OpalSpectralRender(Input=fig12, RefractiveIndex=1.5, ModelRotation=[5, 0, 0], **size))  # noqa: F821
check(numpy.array_equal(by_default, explicit),
      "fig13 by default = fig12's stone turned 5 degrees with the volume's refractive index 1.5")
_, other_index = radiance(OpalSpectralRender(Input=fig13, RefractiveIndex=1.45, **size))  # noqa: F821
check(not numpy.array_equal(by_default, other_index), "a set RefractiveIndex is used as set")
_, turned = radiance(OpalSpectralRender(Input=fig13, ModelRotation=[10, 0, 0], **size))  # noqa: F821
_, fig12_turned_10 = radiance(OpalSpectralRender(Input=fig12, RefractiveIndex=1.5, ModelRotation=[10, 0, 0], **size))  # noqa: F821
check(numpy.allclose(turned, fig12_turned_10, rtol=1e-4, atol=1e-6),
      "ModelRotation is the whole turn: fig13's set to 10 degrees = fig12 turned 10")

path = os.path.join(config.OUTPUT_DIRECTORY, "TestOpalRenderVolumeSettings-fig13.vti")
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
SaveData(path, proxy=fig13, DataMode="Binary")
_, from_file = radiance(OpalSpectralRender(Input=XMLImageDataReader(FileName=[path]), **size))  # noqa: F821
check(numpy.array_equal(by_default, from_file), "the saved fig13 volume renders the same image")

finish("TestOpalRenderVolumeSettings")
