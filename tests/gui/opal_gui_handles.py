"""Run by the ParaView client (paraview --script) under Xvfb for
TestOpalGuiHandles: with a render selected, the 3-D view holds its two
position handles (docs/design.md §5.3), labelled Light and Eye in two
colours; where they coincide (both at 0 60 0) a screenshot shows both
colours, and a drag there moves the Light, not the Eye; the Opal Image View
holds none. The verdict goes to
OPAL_GUI_VERDICT, then the client is ended."""
import os

import numpy
from paraview import servermanager as sm
from paraview.simple import (CreateView, GetActiveViewOrCreate, Hide, LoadPlugin, OutputPort, Render,
                             SaveScreenshot, SetActiveSource, SetActiveView, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from opal_gui_verdict import end_with_verdict

output = os.path.dirname(os.environ["OPAL_GUI_VERDICT"])  # screenshots beside the verdict

lines = []


def handles_in(view):
    """The Opal handles ParaView's panel added to a view: (label, colour) each."""
    found = []
    hidden = view.SMProxy.GetProperty("HiddenRepresentations")  # internal: not a Python attribute
    for proxy in (sm._getPyProxy(hidden.GetProxy(i)) for i in range(hidden.GetNumberOfProxies())):
        if proxy.GetXMLName() == "OpalHandleWidgetRepresentation" and proxy.Visibility:
            found.append((proxy.LabelText, tuple(proxy.HandleColor)))
    return sorted(found)


def handle_positions(view):
    """Where each Opal handle of the view is drawn: {label: (x, y, z)}."""
    hidden = view.SMProxy.GetProperty("HiddenRepresentations")
    handles = [hidden.GetProxy(i) for i in range(hidden.GetNumberOfProxies())]
    return {sm._getPyProxy(h).LabelText: tuple(round(c, 3) for c in h.GetWidget().GetRepresentation().GetWorldPosition())
            for h in handles if h.GetXMLName() == "OpalHandleWidgetRepresentation"}


def drag_from_centre(view, pixels):
    """A left-button drag from the view's centre, `pixels` to the right."""
    interactor = view.GetRenderWindow().GetInteractor()
    x, y = view.ViewSize[0] // 2, view.ViewSize[1] // 2
    for event, at in (("MouseMoveEvent", x), ("LeftButtonPressEvent", x), ("MouseMoveEvent", x + pixels // 2),
                      ("MouseMoveEvent", x + pixels), ("LeftButtonReleaseEvent", x + pixels)):
        interactor.SetEventInformation(at, y, 0, 0, "", 0)
        interactor.InvokeEvent(event)


def pixels_of(path, near):
    """How many pixels of the screenshot lie within 60 levels of the colour `near` (0-255)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    return int(numpy.sum(numpy.all(numpy.abs(rgb - numpy.array(near)) < 60, axis=1)))


try:
    LoadPlugin(os.environ["OPAL_PLUGIN"], remote=False, ns=globals())
    volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821 (from the plugin)
    view = GetActiveViewOrCreate("RenderView")
    Show(OutputPort(volume, 0), view)
    render = OpalSpectralRender(Input=volume, ImageSize=[64, 48])  # noqa: F821
    SetActiveSource(render)  # the panel shows the render: its handles enter the active view
    handles = handles_in(view)
    lines.append(f"3-D view: {handles}")
    labelled = [label for label, _ in handles] == ["Eye", "Light"] and handles[0][1] != handles[1][1]
    Hide(OutputPort(volume, 0), view)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 60, 40], [0, 60, 0], [0, 1, 0]
    view.OrientationAxesVisibility = 0
    Render(view)
    shot = os.path.join(output, "gui-handles.png")
    SaveScreenshot(shot, view, ImageResolution=[400, 300])
    light, eye = pixels_of(shot, [255, 204, 51]), pixels_of(shot, [77, 204, 255])
    lines.append(f"screenshot: {light} light-coloured, {eye} eye-coloured pixels")
    Render(view)
    drag_from_centre(view, 40)  # where both handles sit: the view looks at (0, 60, 0)
    dragged = handle_positions(view)
    lines.append(f"after a drag where both sit: {dragged}")
    light_moved = dragged.get("Eye") == (0, 60, 0) and dragged.get("Light", (0, 60, 0))[0] > 0.05
    image_view = CreateView("OpalImageView")
    Show(render, image_view)
    SetActiveView(image_view)
    in_image = handles_in(image_view)
    lines.append(f"Opal Image View: {in_image}")
    passed = labelled and light > 30 and eye > 30 and light_moved and not in_image
except Exception as error:  # the verdict must be written whatever happens
    lines.append(f"error: {error!r}")
    passed = False
end_with_verdict(lines, passed)
