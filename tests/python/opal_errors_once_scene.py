"""pvbatch helper of TestOpalErrorsOnce (run on a virtual display): a bad
input is reported once and not rendered again until something changes.

For each case of the table (a volume read from a .vti with one array broken,
or a bad render setting) and each way of showing it (the volume with the
"Opal Spectral" representation; Opal Spectral Render's image in a render
view), the error naming the cause appears once over a Show, two Renders and
a direct update of the render filter with nothing changed: no message
repeats, and the input that fails only after a full render (its image would
hold NaN) is not rendered again, which would say so again. Fixed, it renders
with no error.

Prints "opal_errors_once_scene: passed" or the failed checks.
Usage: pvbatch opal_errors_once_scene.py PLUGIN OUTPUT_DIR GOOD_VTI"""
import os
import sys

from paraview.simple import CreateView, Delete, Hide, LoadPlugin, Render, Show, XMLImageDataReader
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkOutputWindow
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter

from opal_test_support import check, failures

plugin, output, good_path = sys.argv[1], sys.argv[2], sys.argv[3]
LoadPlugin(plugin, remote=False, ns=globals())

errors = []


@calldata_type(VTK_STRING)
def record(caller, event, text):
    errors.append(text)


vtkOutputWindow.GetInstance().AddObserver("ErrorEvent", record)

good_reader = vtkXMLImageDataReader()
good_reader.SetFileName(good_path)
good_reader.Update()


def without(name):
    return lambda volume: volume.GetPointData().RemoveArray(name)


def two_components(name):
    def edit(volume):
        one = volume.GetPointData().GetArray(name)
        two = vtkFloatArray()
        two.SetName(name)
        two.SetNumberOfComponents(2)
        two.SetNumberOfTuples(one.GetNumberOfTuples())
        for i in range(one.GetNumberOfTuples()):
            two.SetTuple2(i, one.GetValue(i), 0.0)
        volume.GetPointData().RemoveArray(name)
        volume.GetPointData().AddArray(two)
    return edit


def filled(name, value):
    def edit(volume):
        volume.GetPointData().GetArray(name).Fill(value)
    return edit


def broken_volume(name, edit):
    volume = good_reader.GetOutput().NewInstance()
    volume.DeepCopy(good_reader.GetOutput())
    edit(volume)
    path = os.path.join(output, name + ".vti")
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(volume)
    writer.SetFileName(path)
    writer.Write()
    return path


# (what, the broken volume or None, a bad setting or None, what the error names)
CASES = [
    ("no ScatteringCoefficient", broken_volume("no-scattering", without("ScatteringCoefficient")), None,
     "ScatteringCoefficient"),
    ("ScatteringCoefficient of 2 components",
     broken_volume("two-components", two_components("ScatteringCoefficient")), None, "ScatteringCoefficient"),
    ("no SurfaceDistance", broken_volume("no-surface", without("SurfaceDistance")), None, "SurfaceDistance"),
    # Read and uploaded as it is: only the finished image shows the harm.
    ("SurfaceDistance -3e38: NaN after a full render",
     broken_volume("far-surface", filled("SurfaceDistance", -3e38)), None, "NaN"),
    ("WavelengthStep 0", None, ("WavelengthStep", 0), "WavelengthStep"),
]

view = CreateView("RenderView")
view.ViewSize = [160, 120]


def show_representation(reader):
    """The volume as "Opal Spectral": (the proxy with the render settings,
    the proxy shown, no filter of ours reachable from Python)."""
    display = Show(reader, view)
    display.SetRepresentationType("Opal Spectral")
    return display, reader, None


def show_filter(reader):
    """Opal Spectral Render's image in the view: (the filter's proxy, the
    proxy shown, the filter)."""
    render = OpalSpectralRender(Input=reader, ImageSize=[64, 48])  # noqa: F821 (from the plugin)
    Show(render, view)
    return render, render, render.GetClientSideObject()


def last_lines(messages):
    return [m.strip().splitlines()[-1][:160] for m in messages]


def run_case(what, path, setting, expected, how, show):
    reader = XMLImageDataReader(FileName=[path or good_path])
    del errors[:]
    settings, shown, algorithm = show(reader)
    if setting:
        setattr(settings, *setting)
    view.ResetCamera()
    Render(view)
    first = len(errors)
    Render(view)
    Render(view)
    again = errors[first:]
    if algorithm:
        algorithm.Update()  # below the proxy's short cut: the executive asks the filter again
    named = [e for e in errors if expected in e and "vtkOpalSpectralRender" in e]
    check(len(named) == 1, f"{how}, {what}: the error naming {expected} appears once (got {len(named)}: "
          f"{last_lines(named)})")
    check(not again, f"{how}, {what}: renders with nothing changed add no message (got {last_lines(again)})")
    # Fixed, it renders again with no error.
    del errors[:]
    if setting:
        setattr(settings, setting[0], 10)
    else:
        reader.FileName = [good_path]
    Render(view)
    check(not errors, f"{how}, {what}: fixed, it renders with no error (got {last_lines(errors)})")
    if algorithm:
        check(algorithm.GetOutputDataObject(0).GetNumberOfPoints() == 64 * 48,
              f"{how}, {what}: fixed, the image is made")
    Hide(shown, view)
    if algorithm:
        Delete(settings)
    Delete(reader)


for what, path, setting, expected in CASES:
    run_case(what, path, setting, expected, "representation", show_representation)
    # A bad setting of the filter itself is TestOpalPipelineRecovery's: once
    # its information request failed, ParaView's image display of it is not
    # brought up to date by a render after the fix (an UpdatePipeline is).
    if not setting:
        run_case(what, path, setting, expected, "render filter", show_filter)

print("opal_errors_once_scene:", "FAILED" if failures else "passed")
