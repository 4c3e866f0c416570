"""pvpython: examples/opal_inspect.py runs headless under pvbatch (xvfb), and
its screenshot is not blank: the render's quarter holds the opal's colours
(saturated, bright pixels) and the chart's quarter holds a curve."""
import os

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import opal_test_config as config
from opal_test_support import check, finish, on_virtual_display, run

here = os.path.dirname(os.path.abspath(__file__))
example = os.path.join(here, "..", "..", "examples", "opal_inspect.py")
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
screenshot = os.path.join(config.OUTPUT_DIRECTORY, "inspect.png")
state = os.path.join(config.OUTPUT_DIRECTORY, "inspect.pvsm")
for path in (screenshot, state):
    if os.path.exists(path):
        os.remove(path)
run(on_virtual_display([config.PVBATCH, example, config.PLUGIN, screenshot, "--small", "--state", state]))

reader = vtkPNGReader()
reader.SetFileName(screenshot)
reader.Update()
image = reader.GetOutput()
width, height, _ = image.GetDimensions()
pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int).reshape(height, width, 3)[::-1]


check((width, height) == (1600, 1000), f"screenshot is 1600 x 1000, got {width} x {height}")
render_quarter = pixels[: height // 2, : width // 2]
chroma = render_quarter.max(axis=2) - render_quarter.min(axis=2)
coloured = numpy.mean((chroma > 60) & (render_quarter.max(axis=2) > 120))
bright = numpy.mean(render_quarter.mean(axis=2) > 80)
check(coloured > 0.005, f"the render shows play of colour ({100 * coloured:.2f}% saturated pixels)")
check(bright > 0.05, f"the render shows the milky body ({100 * bright:.1f}% bright pixels)")
check(os.path.getsize(state) > 1000, "the state file was written")
finish("TestOpalInspectExample")
