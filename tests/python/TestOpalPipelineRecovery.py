"""pvpython: a failed render request never poisons the pipeline (issue #16).
A render created with WavelengthStep 0 fails; once the step is fixed the
next update succeeds with no error (none about a stale update extent: a
failed RequestInformation re-announces the last good extent, not the input's,
which the executive had copied) and the output's extent and arrays agree. A
good render given a bad step reports it once, from the filter, and renders
again once fixed."""
from paraview import servermanager as sm
from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonCore import vtkLogger

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821 (from the plugin)


def observed(render):
    """The classes of the objects that report errors for this render (an
    observed error goes to the observer, not to the output window)."""
    errors = []
    algorithm = render.GetClientSideObject()
    for reporter in (algorithm, algorithm.GetExecutive()):
        reporter.AddObserver("ErrorEvent", lambda caller, event: errors.append(caller.GetClassName()))
    return errors


def agrees(render, what):
    extent = tuple(render.GetDataInformation().GetExtent())
    check(extent == (0, 63, 0, 47, 0, 0), f"{what}: the output's extent is the image's (got {extent})")
    image = sm.Fetch(render)
    tuples = image.GetPointData().GetArray("RGB").GetNumberOfTuples()
    check(image.GetNumberOfPoints() == tuples == 64 * 48,
          f"{what}: points and arrays agree ({image.GetNumberOfPoints()} points, {tuples} tuples)")


# Created with a bad step: its first RequestInformation fails (the message is
# expected; the logger's stderr is quiet meanwhile, as ctest fails on "ERR|").
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
born_bad = OpalSpectralRender(Input=volume, ImageSize=[64, 48], WavelengthStep=0)  # noqa: F821
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_INFO)
errors = observed(born_bad)
born_bad.WavelengthStep = 10
born_bad.UpdatePipeline()
check(not errors, f"created failing, fixed: it updates with no error (errors from {errors})")
agrees(born_bad, "created failing, fixed")

good = OpalSpectralRender(Input=volume, ImageSize=[64, 48])  # noqa: F821
good.UpdatePipeline()
errors = observed(good)
good.WavelengthStep = 0
good.UpdatePipeline()
check(errors.count("vtkOpalSpectralRender") == 1, f"a bad step is reported once by the filter (errors from {errors})")
errors.clear()
good.WavelengthStep = 10
good.UpdatePipeline()
check(not errors, f"fixed again: no error (errors from {errors})")
agrees(good, "good, bad, fixed")
finish("TestOpalPipelineRecovery")
