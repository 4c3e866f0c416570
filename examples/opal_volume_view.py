"""Runnable pvpython example: builds an opal volume and saves a picture of its
structure: the diffraction domains as polygons coloured by BraggLambdaMax over
a slice of the scattering coefficient, inside the cabochon's outline. With a
Voronoi preset (harlequin, pinfire) the domains are the ordered grains'
surfaces, which hide the slice: it is left out.

    pvpython examples/opal_volume_view.py PLUGIN OUTPUT.png [PRESET]

PLUGIN is the path of OpalPlugin.so (build/lib/opal/OpalPlugin/OpalPlugin.so).
"""
import sys

from paraview.simple import (ColorBy, Contour, GetActiveViewOrCreate, GetColorTransferFunction,
                             LoadPlugin, OutputPort, SaveScreenshot, Show, Slice)

plugin, output = sys.argv[1], sys.argv[2]
preset = sys.argv[3] if len(sys.argv) > 3 else "fig12"
LoadPlugin(plugin, remote=False, ns=globals())

volume = OpalVolume(Preset=preset)  # noqa: F821 (defined by the plugin)
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [960, 640]
view.UseColorPaletteForBackground = 0
view.Background = [0.08, 0.08, 0.1]
view.OrientationAxesVisibility = 0

# The cabochon's surface, faint.
surface = Contour(Input=OutputPort(volume, 0), ContourBy=["POINTS", "SurfaceDistance"], Isosurfaces=[0.0])
surfaceDisplay = Show(surface, view)
ColorBy(surfaceDisplay, None)
surfaceDisplay.Opacity = 0.15
surfaceDisplay.DiffuseColor = [0.9, 0.9, 0.95]

# A slice through the milky body, coloured by mu_s(550).
if preset not in ("harlequin", "pinfire"):
    body = Slice(Input=OutputPort(volume, 0))
    body.SliceType.Normal = [0, 0, 1]
    body.SliceType.Origin = [0, 4, 0]
    bodyDisplay = Show(body, view)
    ColorBy(bodyDisplay, ("POINTS", "ScatteringCoefficient"))
    bodyDisplay.SetScalarBarVisibility(view, True)
    GetColorTransferFunction("ScatteringCoefficient").ApplyPreset("Grayscale", True)

# The diffraction domains, coloured by the longest wavelength they diffract.
domains = OutputPort(volume, 1)
domainDisplay = Show(domains, view)
ColorBy(domainDisplay, ("CELLS", "BraggLambdaMax"))
# The plugin's own "Visible spectrum" map (each wavelength in its colour) is
# this array's default; its range is the visible spectrum.
lut = GetColorTransferFunction("BraggLambdaMax")
lut.RescaleTransferFunction(380.0, 780.0)
domainDisplay.SetScalarBarVisibility(view, True)

view.CameraPosition = [22, 26, 30]
view.CameraFocalPoint = [0, 2, 0]
view.CameraViewUp = [0, 1, 0]
view.ResetCamera()
SaveScreenshot(output, view, ImageResolution=[960, 640])
print("saved", output)
