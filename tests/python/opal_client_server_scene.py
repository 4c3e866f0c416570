"""Run by TestOpalClientServer (pvpython under Xvfb): shows a small Opal
Volume as "Opal Spectral" in a render view, from a fixed camera, and saves a
screenshot — built in, or connected to a pvserver (one or more ranks) at the
given port, where the representation renders on the server; with "share"
the server's ranks march each frame together (ShareMarch).
Usage: pvpython opal_client_server_scene.py PLUGIN OUT.png [PORT [share]]"""
import sys

from paraview.simple import Connect, CreateView, LoadPlugin, Render, SaveScreenshot, Show

plugin, out = sys.argv[1], sys.argv[2]
if len(sys.argv) > 3:
    Connect("localhost", int(sys.argv[3]))
    LoadPlugin(plugin, remote=True, ns=globals())  # the server's pipeline and representation
LoadPlugin(plugin, remote=False, ns=globals())     # the client's proxies (vtkSMOpal...)
volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821 (from the plugin)
view = CreateView("RenderView")
view.ViewSize = [160, 120]
display = Show(volume, view)
if display.Representation != "Opal Spectral":
    raise RuntimeError(f"shown as {display.Representation}, not Opal Spectral")
display.ShareMarch = int(len(sys.argv) > 4 and sys.argv[4] == "share")
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 40, 0], [0, 2, 0], [0, 0, -1]
view.InteractiveRender()  # a preview, as while the view is dragged (the ranks agree on its scale when shared)
Render(view)
SaveScreenshot(out, view, ImageResolution=[160, 120])
