"""pvpython: examples/opal_tilt_movie.py writes N frames (a PNG series) that
differ from one another as the stone turns, each the spectral render in true
colours pixel for pixel: the middle frame (no turn) equals OpalSpectralRender's
RGB for the same preset and size; OpalSpectralRender's ModelRotation has a
range for the Animation View's default keyframes (-15 to +15 degrees)."""
import glob
import os

import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin, OutputPort
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import opal_test_config as config
from opal_test_support import check, finish, on_virtual_display, run

here = os.path.dirname(os.path.abspath(__file__))
example = os.path.join(here, "..", "..", "examples", "opal_tilt_movie.py")
frames_dir = os.path.join(config.OUTPUT_DIRECTORY, "tilt")
os.makedirs(frames_dir, exist_ok=True)
for old in glob.glob(os.path.join(frames_dir, "*.png")):
    os.remove(old)
width, height = 64, 48
run(on_virtual_display([config.PVBATCH, example, config.PLUGIN, os.path.join(frames_dir, "tilt.png"),
                        "--frames", "3", "--size", str(width), str(height)]))


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    # VTK rows run bottom to top, as the render's own.
    return (w, h), vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int).reshape(h, w, 3)


frames = sorted(glob.glob(os.path.join(frames_dir, "tilt.*.png")))
check(len(frames) == 3, f"3 frames written, got {len(frames)}")
pixels = [read_png(f) for f in frames]
check(all(size == (width, height) for size, _ in pixels), "each frame is 64 x 48")
for a in range(len(pixels)):
    for b in range(a + 1, len(pixels)):
        changed = numpy.mean(numpy.any(pixels[a][1] != pixels[b][1], axis=2))
        check(changed > 0.05, f"frames {a} and {b} differ ({100 * changed:.1f}% of pixels)")

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
volume = OpalVolume(Preset="fig12")  # noqa: F821 (from the plugin)
render = OpalSpectralRender(Input=OutputPort(volume, 0), ImageSize=[width, height])  # noqa: F821
render.UpdatePipeline()
rgb = vtk_to_numpy(sm.Fetch(render).GetPointData().GetArray("RGB")).astype(int).reshape(height, width, 3)
if len(pixels) == 3:
    difference = numpy.abs(pixels[1][1] - rgb)
    check(difference.max() <= 1, f"the middle frame is the render's RGB pixel for pixel (largest difference "
          f"{difference.max()})")
domain = render.GetProperty("ModelRotation").SMProperty.GetDomain("range")
check(domain is not None and domain.GetMinimum(0) == -15 and domain.GetMaximum(0) == 15,
      "ModelRotation's range is -15 to 15 degrees (the Animation View's default keyframes)")
finish("TestOpalTiltMovie")
