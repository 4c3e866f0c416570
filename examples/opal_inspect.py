"""Runnable pvpython / pvbatch example: ParaView as the place to inspect an
opal. For a preset it lays out four views and saves a screenshot:

  - the spectral render (true colours: RGB with Map Scalars off);
  - the domain polygons coloured by BraggWavelength for the render's light,
    inside the cabochon's outline;
  - a slice of VoxelType and one of ScatteringCoefficient;
  - a line chart of the Spectrum of one pixel.

    pvbatch examples/opal_inspect.py PLUGIN OUTPUT.png [--preset fig15]
        [--pixel X Y] [--state OUTPUT.pvsm] [--small]

PLUGIN is build/lib/opal/OpalPlugin/OpalPlugin.so. --small uses a coarse
volume and image (quick, for tests).
"""
import argparse

from paraview.simple import (ColorBy, CreateLayout, CreateView, GetColorTransferFunction,
                             LoadPlugin, OutputPort, ProgrammableFilter, SaveScreenshot, SaveState,
                             Show, Slice, Outline)

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("plugin")
parser.add_argument("output")
parser.add_argument("--preset", default="fig15")
parser.add_argument("--pixel", type=int, nargs=2, default=None, help="pixel (from the top left) whose spectrum to plot")
parser.add_argument("--state", default=None)
parser.add_argument("--small", action="store_true")
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
volume = OpalVolume(Preset=args.preset)  # noqa: F821 (defined by the plugin)
render = OpalSpectralRender(Input=OutputPort(volume, 0), WriteSpectrum=1)  # noqa: F821
size = {"fig15": [300, 300], "fig17": [300, 300]}.get(args.preset, [640, 480])
if args.preset == "fig13":
    render.ModelRotation = [5, 0, 0]
if args.small:
    volume.Dimensions = [80, 40, 100]
    size = [size[0] // 2, size[1] // 2]
render.ImageSize = size
pixel = args.pixel or [size[0] // 2 + size[0] // 8, size[1] // 2]
bragg = OpalBraggMap(Input=OutputPort(volume, 1), LightPosition=render.LightPosition)  # noqa: F821

layout = CreateLayout("Opal " + args.preset)
renderView = CreateView("RenderView")
layout.AssignView(0, renderView)
layout.SplitHorizontal(0, 0.5)
layout.SplitVertical(1, 0.5)
layout.SplitVertical(2, 0.5)
domainView = CreateView("RenderView")
layout.AssignView(4, domainView)
sliceView = CreateView("RenderView")
layout.AssignView(5, sliceView)
chartView = CreateView("XYChartView")
layout.AssignView(6, chartView)
layout.SetSize(1600, 1000)
for view in (renderView, domainView, sliceView):
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.08, 0.08, 0.1]

# 1. The render, in true colours.
imageDisplay = Show(render, renderView)
ColorBy(imageDisplay, ("POINTS", "RGB"))
imageDisplay.MapScalars = 0
renderView.InteractionMode = "2D"
renderView.ResetCamera()
renderView.CameraParallelScale = size[1] / 2.0

# 2. The domains coloured by the wavelength they diffract for the render's light
#    (the "Visible spectrum" colour map is the plugin's default for it).
domainDisplay = Show(bragg, domainView)
ColorBy(domainDisplay, ("CELLS", "BraggWavelength"))
# ParaView fits a new colour map to the data; show the whole visible range.
GetColorTransferFunction("BraggWavelength").RescaleTransferFunction(380.0, 780.0)
domainDisplay.SetScalarBarVisibility(domainView, True)
Show(Outline(Input=OutputPort(volume, 0)), domainView)
domainView.CameraPosition = [0, 60, 0]
domainView.CameraFocalPoint = [0, 0, 0]
domainView.CameraViewUp = [0, 0, -1]
domainView.ResetCamera()

# 3. VoxelType across the middle (x = 0), ScatteringCoefficient across the base (y = 1 mm).
types = Slice(Input=OutputPort(volume, 0))
types.SliceType.Origin = [0, 4, 0]
types.SliceType.Normal = [1, 0, 0]
typeDisplay = Show(types, sliceView)
typeDisplay.Ambient, typeDisplay.Diffuse = 1.0, 0.0  # slices unlit: true field colours
ColorBy(typeDisplay, ("POINTS", "VoxelType"))
typeDisplay.SetScalarBarVisibility(sliceView, True)
scattering = Slice(Input=OutputPort(volume, 0))
scattering.SliceType.Origin = [0, 1, 0]
scattering.SliceType.Normal = [0, 1, 0]
scatteringDisplay = Show(scattering, sliceView)
scatteringDisplay.Ambient, scatteringDisplay.Diffuse = 1.0, 0.0
ColorBy(scatteringDisplay, ("POINTS", "ScatteringCoefficient"))
GetColorTransferFunction("ScatteringCoefficient").ApplyPreset("Grayscale", True)
scatteringDisplay.SetScalarBarVisibility(sliceView, True)
sliceView.CameraPosition = [30, 25, 30]
sliceView.CameraFocalPoint = [0, 2, 0]
sliceView.CameraViewUp = [0, 1, 0]
sliceView.ResetCamera()

# 4. The spectrum of one pixel as a table of (wavelength, radiance).
spectrum = ProgrammableFilter(Input=render)
spectrum.OutputDataSetType = "vtkTable"
spectrum.Script = f"""
from vtkmodules.vtkCommonCore import vtkFloatArray
image = self.GetInputDataObject(0, 0)
table = self.GetOutputDataObject(0)
dims = image.GetDimensions()
x, y = {pixel[0]}, dims[1] - 1 - {pixel[1]}
values = image.GetPointData().GetArray("Spectrum")
lambdas = image.GetFieldData().GetArray("Wavelengths")
wavelength, radiance = vtkFloatArray(), vtkFloatArray()
wavelength.SetName("Wavelength (nm)")
radiance.SetName("Spectral radiance at pixel ({pixel[0]}, {pixel[1]})")
if values is not None and lambdas is not None:
    point = x + dims[0] * y
    for l in range(lambdas.GetNumberOfTuples()):
        wavelength.InsertNextValue(lambdas.GetValue(l))
        radiance.InsertNextValue(values.GetComponent(point, l))
table.AddColumn(wavelength)
table.AddColumn(radiance)
"""
chart = Show(spectrum, chartView)
chart.UseIndexForXAxis = 0
chart.XArrayName = "Wavelength (nm)"
chart.SeriesVisibility = [f"Spectral radiance at pixel ({pixel[0]}, {pixel[1]})"]
chartView.LeftAxisTitle = "spectral radiance"
chartView.BottomAxisTitle = "wavelength (nm)"

SaveScreenshot(args.output, layout, ImageResolution=[1600, 1000])
if args.state:
    SaveState(args.state)
print("saved", args.output)
