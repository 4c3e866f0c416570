"""Run by the ParaView client (paraview --script) under Xvfb for
TestOpalGuiLiveView: in the GUI's own render view, the Opal Volume is shown as
"Opal Spectral" by default (the cabochon in colour, not an outline), and the
camera turned 10 degrees between two renders changes the stone's pixels. The verdict goes to OPAL_GUI_VERDICT (the client's
stdout is not the test's), then the client is ended."""
import os

import numpy
from paraview.simple import GetActiveViewOrCreate, LoadPlugin, OutputPort, Render, SaveScreenshot, Show
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from opal_gui_verdict import end_with_verdict

output = os.path.dirname(os.environ["OPAL_GUI_VERDICT"])  # screenshots beside the verdict

lines = []


def screenshot(view, path):
    SaveScreenshot(path, view, ImageResolution=[320, 240])
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)


try:
    LoadPlugin(os.environ["OPAL_PLUGIN"], remote=False, ns=globals())
    volume = OpalVolume(Dimensions=[80, 40, 100], DomainCount=120)  # noqa: F821 (from the plugin)
    view = GetActiveViewOrCreate("RenderView")
    stone = Show(OutputPort(volume, 0), view)  # shown as "Opal Spectral" by default
    lines.append(f"representation {stone.Representation}")
    Render(view)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 40, 0], [0, 2, 0], [0, 0, -1]
    Render(view)
    before = screenshot(view, os.path.join(output, "gui-live-before.png"))
    view.GetActiveCamera().Azimuth(10)
    Render(view)
    after = screenshot(view, os.path.join(output, "gui-live-after.png"))
    background = before[0]  # a corner: the view's background
    stone_share = numpy.mean(numpy.any(numpy.abs(before - background) > 12, axis=1))
    changed = numpy.mean(numpy.any(numpy.abs(before - after) > 8, axis=1))
    lines.append(f"stone {100 * stone_share:.0f}% of the view, {100 * changed:.1f}% of pixels changed")
    chroma = before.max(axis=1) - before.min(axis=1)
    coloured = numpy.mean(chroma > 60)
    lines.append(f"{100 * coloured:.1f}% of the view saturated colours (the domains' play of colour)")
    passed = (stone.Representation == "Opal Spectral" and 0.1 < stone_share < 0.95 and changed > 0.02 and
              coloured > 0.002)
except Exception as error:  # the verdict must be written whatever happens
    lines.append(f"error: {error!r}")
    passed = False
end_with_verdict(lines, passed)
