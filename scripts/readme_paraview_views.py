"""Makes the README's figure docs/images/paraview-views.png: the two views a
new user sees after Sources > Opal Volume (fig12) and Filters > Opal Spectral
Render, side by side as ParaView lays them out (1280 x 480): the stone live in
the 3-D view (Opal Spectral), seen from above as the first view is (the
camera left to the volume's proxy, as after the GUI's Apply:
TestOpalGuiApplyView); the render's image in the Opal Image View (2-D, true
colours, no colour bar; the Light and Eye handles are drawn in 3-D views only,
docs/design.md §5.3). pvbatch renders each still frame before the view draws
it (the GUI's background frames are the GUI's alone), so the screenshots hold
the final frames; a view without the stone fails the script.
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvbatch scripts/readme_paraview_views.py PLUGIN OUTPUT.png"""
import os
import sys
import tempfile

import numpy
from paraview.simple import CreateView, LoadPlugin, OutputPort, Render, SaveScreenshot, Show
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

plugin, output = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())
volume = OpalVolume(Preset="fig12")  # noqa: F821 (from the plugin)
render = OpalSpectralRender(Input=volume)  # noqa: F821


def shot(view):
    """A 639 x 480 screenshot of the view, rows bottom up (VTK's order)."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "view.png")
        SaveScreenshot(path, view, ImageResolution=[639, 480])
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].reshape(480, 639, 3)


stone_view = CreateView("RenderView")
Show(OutputPort(volume, 0), stone_view)
Render(stone_view)  # the first render: the volume's proxy looks down on the stone
image_view = CreateView("OpalImageView")
Show(render, image_view)
image_view.ResetCamera()
Render(image_view)
left, right = shot(stone_view), shot(image_view)
for name, view in (("3-D view", left), ("image view", right)):
    shown = numpy.abs(view.astype(int) - view[477, 320]).max(axis=2) > 12  # against the background
    if shown.mean() < 0.1:
        sys.exit(f"the {name} shows no stone ({100 * shown.mean():.1f}% of it differs from its background)")
separator = numpy.full((480, 2, 3), 255, dtype=numpy.uint8)  # the layout's splitter
image = vtkImageData()
image.SetDimensions(1280, 480, 1)
image.GetPointData().SetScalars(numpy_to_vtk(numpy.concatenate([left, separator, right], axis=1).reshape(-1, 3)))
writer = vtkPNGWriter()
writer.SetFileName(output)
writer.SetInputData(image)
writer.Write()
