"""pvpython: the plugin's three proxies exist with every property documented;
the Opal Bragg Map equals the closed form (paper eq. 3-5, docs/design.md §3.1)
at sampled diffraction voxels and changes with the light position as the
formula says; its colour map defaults to the visible spectrum."""

import numpy
from paraview import servermanager as sm
from paraview.simple import CreateView, GetColorTransferFunction, LoadPlugin, OutputPort, Show
from vtkmodules.util.numpy_support import vtk_to_numpy

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())


volume = OpalVolume(Dimensions=[80, 40, 100])  # noqa: F821 (from the plugin)
render = OpalSpectralRender(Input=volume, ImageSize=[32, 24])  # noqa: F821
bragg = OpalBraggMap(Input=volume)  # noqa: F821
for proxy, expected in ((volume, ["Preset", "Dimensions", "DomainCount", "Seed"]),
                        (render, ["ImageSize", "LightPosition", "EyePosition", "WavelengthStep",
                                  "BraggBandwidth", "DiffractionGain", "MosaicSpread", "Exposure",
                                  "StepSize", "WriteSpectrum"]),
                        (bragg, ["LightPosition", "EyePosition", "RefractiveIndex", "BraggOrder",
                                 "MosaicSpread"])):
    name = proxy.GetXMLLabel()
    properties = proxy.ListProperties()
    for prop in expected:
        check(prop in properties, f"{name} has the property {prop}")
    for prop in properties:
        documentation = proxy.GetProperty(prop).SMProperty.GetDocumentation()
        check(documentation is not None and documentation.GetDescription().strip(),
              f"{name}.{prop} is documented")


def bragg_closed_form(points, normals, diameters, light, mu=1.45, order=1):
    """lambda_B = 2 d sqrt(mu^2 - cos^2 theta1) / k, d = sqrt(2/3) l, theta1 the glancing angle."""
    to_light = light - points
    to_light /= numpy.linalg.norm(to_light, axis=1)[:, None]
    sin_glancing = numpy.abs(numpy.sum(to_light * normals, axis=1)) / numpy.linalg.norm(normals, axis=1)
    d = numpy.sqrt(2.0 / 3.0) * diameters
    return 2.0 * d * numpy.sqrt(mu * mu - (1.0 - sin_glancing ** 2)) / order


def sampled(light):
    bragg.LightPosition = light
    bragg.UpdatePipeline()
    data = sm.Fetch(bragg)
    pd = data.GetPointData()
    ids = vtk_to_numpy(pd.GetArray("DomainId"))
    voxels = numpy.nonzero(ids >= 0)[0][::37]
    points = numpy.array([data.GetPoint(int(i)) for i in voxels])
    normals = vtk_to_numpy(pd.GetArray("Normal"))[voxels]
    diameters = vtk_to_numpy(pd.GetArray("ParticleDiameter"))[voxels].astype(float)
    got = vtk_to_numpy(pd.GetArray("BraggWavelength"))[voxels]
    expected = bragg_closed_form(points, normals, diameters, numpy.array(light, dtype=float))
    outside = vtk_to_numpy(pd.GetArray("BraggWavelength"))[ids < 0]
    visible = vtk_to_numpy(pd.GetArray("BraggVisible"))[voxels]
    colour = vtk_to_numpy(pd.GetArray("BraggColor"))[voxels]
    return voxels, got, expected, outside, visible, colour


paper = [0.0, 60.0, 0.0]
voxels, got, expected, outside, visible, colour = sampled(paper)
check(len(voxels) > 50, f"many diffraction voxels sampled ({len(voxels)})")
check(numpy.allclose(got, expected, rtol=1e-5), "BraggWavelength equals the closed form (paper's light), "
      f"worst relative error {numpy.max(numpy.abs(got - expected) / expected)}")
check(numpy.all(outside == 0), "BraggWavelength is 0 outside domains")
in_range = (expected >= 380) & (expected <= 780)
check(numpy.array_equal(visible > 0, in_range), "BraggVisible marks exactly the visible wavelengths")
check(numpy.all(colour[in_range].max(axis=1) > 0) and numpy.all(colour[~in_range] == 0),
      "BraggColor is coloured for visible wavelengths, black otherwise")

oblique = [12.0, 30.0, -8.0]
_, got2, expected2, _, _, _ = sampled(oblique)
check(numpy.allclose(got2, expected2, rtol=1e-5), "BraggWavelength follows the closed form for an oblique light")
check(numpy.mean(numpy.abs(got2 - got)) > 1.0, "moving the light changes the Bragg wavelengths")
check(numpy.allclose(got2 - got, expected2 - expected, atol=0.05), "they change as the formula says")

polygons = OpalBraggMap(Input=OutputPort(volume, 1))  # noqa: F821
polygons.UpdatePipeline()
cells = sm.Fetch(polygons).GetCellData()
check(cells.GetArray("BraggWavelength") is not None and cells.GetArray("BraggColor") is not None,
      "the Bragg map works on the domain polygons (cell data)")

# One refractive index: the Bragg map's default (0) takes the volume's.
denser = OpalVolume(Dimensions=[40, 20, 50], DomainCount=20, RefractiveIndex=1.6)  # noqa: F821
denserMap = OpalBraggMap(Input=denser, LightPosition=[0, 60, 0])  # noqa: F821
denserMap.UpdatePipeline()
data = sm.Fetch(denserMap)
pd = data.GetPointData()
ids = vtk_to_numpy(pd.GetArray("DomainId"))
voxels = numpy.nonzero(ids >= 0)[0][::11]
expected = bragg_closed_form(numpy.array([data.GetPoint(int(i)) for i in voxels]),
                             vtk_to_numpy(pd.GetArray("Normal"))[voxels],
                             vtk_to_numpy(pd.GetArray("ParticleDiameter"))[voxels].astype(float),
                             numpy.array([0.0, 60.0, 0.0]), mu=1.6)
got = vtk_to_numpy(pd.GetArray("BraggWavelength"))[voxels]
check(len(voxels) > 0 and numpy.allclose(got, expected, rtol=1e-4),
      "the Bragg map's default refractive index is the volume's (1.6)")

lut = GetColorTransferFunction("DominantBraggWavelength")
points = list(lut.RGBPoints)
check(points[0] == 380.0 and points[-4] == 780.0 and len(points) > 40,
      "the Visible spectrum colour map is the default for DominantBraggWavelength")
at750 = points[points.index(750.0) + 1:points.index(750.0) + 4]
check(at750[0] > at750[1] and at750[0] > at750[2] and at750[0] < 0.5,
      f"the colour map shows 750 nm as dark red, not pink: {at750}")

for proxy in (volume, render, bragg):
    hints = proxy.GetHints()
    menus = [hints.GetNestedElement(i) for i in range(hints.GetNumberOfNestedElements())] if hints else []
    check(any(m.GetName() == "ShowInMenu" and m.GetAttribute("category") == "Opal" for m in menus),
          f"{proxy.GetXMLName()} is in the Opal menu category")

# First views: ParaView colours a new display by the data's active scalars
# (read from the filters themselves: Fetch's gather does not keep them).
volume.UpdatePipeline()
domains = volume.GetClientSideObject().GetOutputDataObject(1)
check(domains.GetCellData().GetScalars() is not None and
      domains.GetCellData().GetScalars().GetName() == "BraggLambdaMax",
      "the Domains output's active scalars are BraggLambdaMax (shown in the Visible spectrum map)")
on_domains = OpalBraggMap(Input=OutputPort(volume, 1))  # noqa: F821 (from the plugin)
on_domains.UpdatePipeline()
mapped = on_domains.GetClientSideObject().GetOutputDataObject(0).GetCellData().GetScalars()
check(mapped is not None and mapped.GetName() == "BraggWavelength",
      "the Bragg map's active scalars are BraggWavelength")

# The panel's search: for a group drawn by one widget (the Light and Eye
# handles) ParaView matches the group's label and widget name, not the
# properties' names, so the labels carry the words a user types.
for proxy in (render, bragg):
    groups = [proxy.SMProxy.GetPropertyGroup(i) for i in range(proxy.SMProxy.GetNumberOfPropertyGroups())]
    handles = {g.GetProperty(0).GetXMLName(): [g.GetXMLLabel() or "", g.GetPanelWidget()]
               for g in groups if g.GetPanelWidget() == "OpalHandle"}
    found = {word: sorted(name for name, tags in handles.items() if any(word in t.lower() for t in tags))
             for word in ("position", "eye", "light")}
    check(found == {"position": ["EyePosition", "LightPosition"], "eye": ["EyePosition"],
                    "light": ["LightPosition"]},
          f"{proxy.GetXMLName()}: searching position/eye/light finds the handles {found}")

# The render's image: ParaView's Apply shows it in an Opal Image View of its
# own (the View hint), in true colours (Map Scalars off), and the pipeline
# browser has an icon for it (no "Could not find icon pixmap" warning).
controller = sm.vtkSMParaViewPipelineControllerWithRendering()
check(controller.GetPreferredViewType(render.SMProxy, 0) == "OpalImageView",
      "the render's image opens in an Opal Image View")
check(controller.GetPipelineIcon(render.SMProxy, 0) == "GEOMETRY", "the render's pipeline icon is ParaView's own")
image_view = CreateView("OpalImageView")
check(image_view.InteractionMode == "2D" and image_view.CameraParallelProjection == 1 and
      image_view.OrientationAxesVisibility == 0, "the Opal Image View starts in 2-D, parallel, without axes")
display = Show(render, image_view)
check(display.MapScalars == 0 and list(display.ColorArrayName) == ["POINTS", "RGB"],
      f"the image is shown in its RGB colours, unmapped (MapScalars {display.MapScalars})")

# A Bragg map keeps the stone shown (replace_input 0) and shows, on the volume,
# its domains only: a volume rendering of BraggWavelength in the Visible
# spectrum map, nearest voxels, transparent below 380 nm (outside domains);
# on the domain polygons, their surfaces in the same map.
bragg_hints = bragg.GetHints()
visibility = [bragg_hints.GetNestedElement(i) for i in range(bragg_hints.GetNumberOfNestedElements())
              if bragg_hints.GetNestedElement(i).GetName() == "Visibility"]
check(len(visibility) == 1 and visibility[0].GetAttribute("replace_input") == "0",
      "a Bragg map leaves the stone shown")
map_view = CreateView("RenderView")
on_volume = Show(bragg, map_view)
opacity = list(on_volume.ScalarOpacityFunction.Points)
check(on_volume.Representation == "Volume" and list(on_volume.ColorArrayName) == ["POINTS", "BraggWavelength"] and
      on_volume.InterpolationType == "Nearest",
      f"the volume's Bragg map is its domains by BraggWavelength: {on_volume.Representation}, "
      f"{list(on_volume.ColorArrayName)}, {on_volume.InterpolationType}")
check(opacity[1] == 0 and opacity[4] < 380 and opacity[5] == 0 and opacity[8] == 380 and opacity[9] == 1,
      f"outside domains (0 nm) is transparent, every visible wavelength opaque: {opacity}")
check(list(on_volume.LookupTable.RGBPoints)[0] == 380.0, "the Bragg map is in the Visible spectrum map")
on_polygons = Show(polygons, map_view)
check(on_polygons.Representation == "Surface" and list(on_polygons.ColorArrayName) == ["CELLS", "BraggWavelength"],
      f"the domain polygons' Bragg map: {on_polygons.Representation} by {list(on_polygons.ColorArrayName)}")

# The Domains output waits until asked for: Apply shows it in no view (the
# View hint "None"), with ParaView's own pipeline icon; Show still shows it.
check(controller.GetPreferredViewType(volume.SMProxy, 1) == "None" and
      controller.GetPipelineIcon(volume.SMProxy, 1) == "GEOMETRY",
      "the Domains output is not shown on Apply and has ParaView's geometry icon")
check(controller.ShowInPreferredView(volume.SMProxy, 1, CreateView("RenderView").SMProxy) is None,
      "showing the volume's outputs where they belong leaves the Domains hidden")

# The first view: a render view that first shows the Volume output looks down
# on the stone from +y (the render's default eye, focal point and view up:
# the paper's set-up, where the domains flash), the stone framed; a camera a
# script set first is kept.
above = CreateView("RenderView")
above.ViewSize = [64, 48]
# (Outline: Opal Spectral renders where the data are, which needs a display.)
Show(OutputPort(volume, 0), above).Representation = "Outline"
above.Update()  # the data reach the view (no display here: no render)
direction = numpy.subtract(above.CameraPosition, above.CameraFocalPoint)
check(numpy.allclose(direction / numpy.linalg.norm(direction), [0, 1, 0]) and
      numpy.allclose(above.CameraViewUp, [0, 0, -1]) and numpy.allclose(above.CameraFocalPoint, [0, 4, 0]),
      f"the first view looks down on the stone: eye {list(above.CameraPosition)}, "
      f"focal point {list(above.CameraFocalPoint)}, up {list(above.CameraViewUp)}")
placed = CreateView("RenderView")
placed.ViewSize = [64, 48]
Show(OutputPort(volume, 0), placed).Representation = "Outline"
placed.CameraPosition, placed.CameraFocalPoint, placed.CameraViewUp = [0, 4, 60], [0, 4, 0], [0, 1, 0]
placed.Update()
check(list(placed.CameraPosition) == [0, 4, 60] and list(placed.CameraViewUp) == [0, 1, 0],
      f"a camera set by a script before the first render is kept: {list(placed.CameraPosition)}")

finish("TestOpalPluginProxies")
