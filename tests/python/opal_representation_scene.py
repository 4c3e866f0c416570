"""pvbatch helper of TestOpalSpectralRepresentation (run on a virtual display):
shows a small Opal Volume with the "Opal Spectral" representation and checks
what the view shows.

- The volume is shown as "Opal Spectral" first (its proxy's hint); a kind of
  opal's representation shows its preset's Bragg model and planes.
- Two camera directions 10 degrees apart: both show the stone (most of its
  box's footprint is not background) and the domains' hues differ.
- The still frame equals Opal Spectral Render's image for the same camera
  (eye, focal point, view up, view angle, the light at the eye), pixel for
  pixel within 1 level: the representation is that render, drawn 1:1.
- A render setting set on the representation (MosaicSpread, exposed from its
  Opal Spectral Render SubProxy) reaches its frames as the filter's does.
- An interactive render (ParaView's, as during a drag) draws a preview,
  not the still frame; the still render after it is final again.
- Depth: a plane between the eye and the stone hides it; the same plane
  behind the stone is hidden by it.
- A screenshot twice the view's size (drawn by ParaView in 2 x 2 tiles)
  equals a screenshot of a view that size.
- An eye inside the stone's box but outside the stone (above the dome's
  flank) sees the stone; an eye inside the stone sees nothing of it.

Prints "opal_representation_scene: passed" or the failed checks.
Usage: pvbatch opal_representation_scene.py PLUGIN OUTPUT_DIR"""
import os
import sys

import numpy
from paraview import servermanager as sm
from paraview.simple import (ColorBy, CreateView, Delete, Hide, LoadPlugin, OutputPort, Plane, Render, SaveScreenshot,
                             Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

from opal_test_support import check, failures

plugin, output = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())
width, height = 160, 120

volume = OpalVolume(Preset="fig11", Dimensions=[80, 40, 100], DomainCount=120)  # noqa: F821 (the preset first: it sets DomainCount)
view = CreateView("RenderView")
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0, 0, 0]
view.UseFXAA = 0
stone = Show(OutputPort(volume, 0), view)
check(stone.Representation == "Opal Spectral", f"the volume is shown as Opal Spectral first ({stone.Representation})")
stone.SetRepresentationType("Opal Spectral")
Render(view)  # the first render resets the camera; the cameras below are set after it

# A kind of opal's representation takes its preset's Bragg model and planes (docs/design.md §2.11).
kind = OpalVolume(Preset="black-opal", Dimensions=[20, 10, 24], DomainCount=5)  # noqa: F821
kind_display = Show(OutputPort(kind, 0), view)
check(kind_display.BraggModel == "coupled-wave" and kind_display.LatticePlanes == "fcc",
      f"black-opal is shown with its Bragg model and planes: {kind_display.BraggModel}, {kind_display.LatticePlanes}")
kind.Preset = "fig12"
check(kind_display.BraggModel == "paper" and kind_display.LatticePlanes == "111",
      f"choosing fig12 shows the paper's model: {kind_display.BraggModel}, {kind_display.LatticePlanes}")
Hide(OutputPort(kind, 0), view)
Delete(kind)


def look_from(eye):
    view.CameraPosition = eye
    view.CameraFocalPoint = [0, 2, 0]
    view.CameraViewUp = [0, 0, -1]
    view.CameraViewAngle = 30
    Render(view)


def screenshot(name):
    path = os.path.join(output, name)
    SaveScreenshot(path, view, ImageResolution=[width, height])
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int).reshape(height, width, 3)


def hue(pixels):
    """Mean hue angle (degrees) of the saturated pixels: the domains' colours."""
    rgb = pixels.reshape(-1, 3).astype(float)
    saturated = rgb[(rgb.max(axis=1) - rgb.min(axis=1)) > 40]
    if len(saturated) == 0:
        return None
    r, g, b = saturated[:, 0], saturated[:, 1], saturated[:, 2]
    return numpy.degrees(numpy.arctan2(numpy.sqrt(3) * (g - b), 2 * r - g - b)).mean()


# Two directions 10 degrees apart, about the stone's long axis (z).
first_eye = [0.0, 36.0, 0.0]
second_eye = [36.0 * numpy.sin(numpy.radians(10)), 36.0 * numpy.cos(numpy.radians(10)), 0.0]
look_from(first_eye)
first = screenshot("representation-0deg.png")
look_from(second_eye)
second = screenshot("representation-10deg.png")
for name, pixels in (("0 degrees", first), ("10 degrees", second)):
    stone_share = numpy.mean(pixels.max(axis=2) > 20)
    check(stone_share > 0.25, f"{name}: the stone fills {100 * stone_share:.0f}% of the view (> 25%)")
changed = numpy.mean(numpy.any(numpy.abs(first - second) > 8, axis=2))
check(changed > 0.02, f"turning 10 degrees changes the picture ({100 * changed:.1f}% of pixels)")
hues = (hue(first), hue(second))
check(None not in hues and abs(hues[0] - hues[1]) > 1.0, f"the domains' hues move with the view: {hues}")

# The still frame is Opal Spectral Render's image for the same camera.
render = OpalSpectralRender(Input=OutputPort(volume, 0), ImageSize=[width, height],  # noqa: F821
                            EyePosition=second_eye, FocalPoint=[0, 2, 0], ViewUp=[0, 0, -1], ViewAngle=30,
                            LightPosition=second_eye)
render.UpdatePipeline()
rgb = vtk_to_numpy(sm.Fetch(render).GetPointData().GetArray("RGB")).astype(int).reshape(height, width, 3)
difference = numpy.abs(second - rgb)
check(difference.max() <= 1, f"the still frame is the render's image pixel for pixel (largest difference "
      f"{difference.max()}, {numpy.mean(difference.max(axis=2) > 1) * 100:.2f}% of pixels off)")

# The representation's render settings are Opal Spectral Render's own
# properties (its SubProxy): a change reaches the frames, and equals the
# filter's image with the same setting.
stone.MosaicSpread = render.MosaicSpread = 5.0
Render(view)
gated = screenshot("representation-10deg-mosaic.png")
render.UpdatePipeline()
rgb = vtk_to_numpy(sm.Fetch(render).GetPointData().GetArray("RGB")).astype(int).reshape(height, width, 3)
check(numpy.mean(numpy.any(numpy.abs(gated - second) > 8, axis=2)) > 0.01 and numpy.abs(gated - rgb).max() <= 1,
      "a MosaicSpread set on the representation reaches its frames, as the render's own property")
stone.MosaicSpread = 0.0
Render(view)

# An interactive render (as during a drag) draws a preview: the stone at half
# the resolution, not the still frame; the still render after it is final again.
view.SMProxy.InteractiveRender()
grab = vtkWindowToImageFilter()
grab.SetInput(view.GetRenderWindow())
grab.ShouldRerenderOff()
grab.ReadFrontBufferOff()
grab.Update()
grabbed = grab.GetOutput()
w, h, _ = grabbed.GetDimensions()
preview = vtk_to_numpy(grabbed.GetPointData().GetScalars())[:, :3].astype(int).reshape(h, w, 3)
if (w, h) == (width, height):
    preview_share = numpy.mean(preview.max(axis=2) > 20)
    off = numpy.mean(numpy.abs(preview - second).max(axis=2) > 8)
    check(preview_share > 0.25, f"the preview shows the stone ({100 * preview_share:.0f}% of the view)")
    check(off > 0.02, f"the preview is not the still frame ({100 * off:.1f}% of pixels differ)")
else:
    check(False, f"the interactive frame is grabbed at the view's size (got {w} x {h})")
Render(view)
again = screenshot("representation-10deg-again.png")
check(numpy.abs(again - second).max() <= 1, "the still render after it is the final frame again")

# Depth: an opaque plane (a stand-in for the Domains output or a slice) in
# front of the stone hides it, behind it is hidden.
look_from(first_eye)
plane = Plane(Origin=[-20, 0, -20], Point1=[20, 0, -20], Point2=[-20, 0, 20])
plane_display = Show(plane, view)
plane_display.ColorArrayName = ["POINTS", ""]
plane_display.AmbientColor = plane_display.DiffuseColor = [0, 0, 1]
plane_display.Ambient, plane_display.Diffuse = 1.0, 0.0
centre = (slice(height // 2 - 5, height // 2 + 5), slice(width // 2 - 5, width // 2 + 5))
for y, where in ((20.0, "in front of"), (-1.0, "behind")):
    plane.Origin, plane.Point1, plane.Point2 = [-20, y, -20], [20, y, -20], [-20, y, 20]
    Render(view)
    pixels = screenshot(f"representation-plane-{'front' if y > 0 else 'behind'}.png")[centre]
    blue = numpy.mean((pixels[..., 2] > 200) & (pixels[..., 0] < 50) & (pixels[..., 1] < 50))
    if y > 0:
        check(blue > 0.95, f"a plane {where} the stone hides it ({100 * blue:.0f}% of the centre blue)")
    else:
        check(blue < 0.05, f"a plane {where} the stone is hidden by it ({100 * blue:.0f}% of the centre blue)")
Hide(plane, view)

# A screenshot larger than the view: ParaView renders it in tiles, each with
# a narrower, off-centre camera; the stone must come out as in a view of that
# size, not once per tile (the seams' texture sampling moves a few pixels).
def shot_at(view_size, resolution, name):
    view.ViewSize = view_size
    Render(view)
    path = os.path.join(output, name)
    SaveScreenshot(path, view, ImageResolution=resolution)
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)


big = [2 * width, 2 * height]
tiled = shot_at([width, height], big, "representation-tiled.png")
whole = shot_at(big, big, "representation-whole.png")
differing = numpy.mean(numpy.any(numpy.abs(tiled - whole) > 8, axis=1))
check(differing < 0.01, f"a 2 x 2 tiled screenshot equals a view of its size ({100 * differing:.2f}% of pixels differ)")
view.ViewSize = [width, height]
# The box reaches over the dome's flanks: an eye there is outside the stone.
bounds = volume.GetDataInformation().GetBounds()
view.ViewSize = [width, height]
view.CameraPosition = [0.9 * bounds[1], 0.9 * bounds[3], 0.5 * bounds[5]]
view.CameraFocalPoint, view.CameraViewUp, view.CameraViewAngle = [0, 0, 0], [0, 0, -1], 60
in_box = screenshot("representation-eye-in-box.png")
check(numpy.mean(in_box.max(axis=2) > 20) > 0.2, f"an eye in the stone's box, outside the stone, sees it "
      f"({100 * numpy.mean(in_box.max(axis=2) > 20):.0f}% of the view)")
view.CameraPosition = [0, 0.2 * bounds[3], 0]
inside = screenshot("representation-eye-inside.png")
check(inside.max() <= 20, "an eye inside the stone sees nothing of it")
# The verdict on stdout, for the test; the script ends normally (pvbatch
# reports an X error when sys.exit ends it with a window open).
print("opal_representation_scene:", "FAILED" if failures else "passed")
