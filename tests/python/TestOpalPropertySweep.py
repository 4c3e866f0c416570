"""pvpython: every numeric property of the three proxies (OpalVolume,
OpalSpectralRender, OpalBraggMap), found by listing them, set to NaN, +Inf,
-1, the largest double, the smallest denormal and 0, one at a time on a small
volume: the request is refused with an error naming the property (observed
on the filter, so it is not printed) or its outputs are finite. Never
a crash of the process (the test would not finish) nor a NaN or an infinity
in a point array (issue #16)."""
import numpy
from paraview import servermanager as sm
from paraview.simple import Delete, LoadPlugin
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING, vtkLogger

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
VALUES = [float("nan"), float("inf"), -1.0, 1.7976931348623157e308, 5e-324, 0.0]
SMALL = dict(Dimensions=[20, 10, 25], DomainCount=5)


def numeric_properties(proxy):
    """(name, number of values) of each property holding numbers."""
    found = []
    for name in proxy.ListProperties():
        try:
            value = proxy.GetProperty(name).GetData()
        except Exception:
            continue
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            found.append((name, 1))
        elif isinstance(value, list) and value and all(isinstance(v, (int, float)) for v in value):
            found.append((name, len(value)))
    return found


def non_finite_array(proxy):
    """The name of a point array holding a NaN or an infinity, or None."""
    data = sm.Fetch(proxy)
    points = data.GetPointData() if data is not None else None
    for i in range(points.GetNumberOfArrays() if points is not None else 0):
        array = points.GetArray(i)
        if array is not None and not numpy.all(numpy.isfinite(vtk_to_numpy(array))):
            return array.GetName()
    return None


def observe_errors(proxy):
    """The error messages the proxy's filter reports from now on."""
    messages = []

    @calldata_type(VTK_STRING)
    def record(caller, event, message):
        messages.append(message)

    proxy.GetClientSideObject().AddObserver("ErrorEvent", record)
    return messages


refusals = []


def sweep(make, label):
    probe = make()
    properties = numeric_properties(probe)
    Delete(probe)
    check(len(properties) >= 5, f"{label}: its numeric properties are found ({len(properties)})")
    for name, count in properties:
        for value in VALUES:
            proxy = make()
            try:
                setattr(proxy, name, [value] * count if count > 1 else value)
            except Exception:
                Delete(proxy)  # refused by the property itself
                continue
            errors = observe_errors(proxy)
            proxy.UpdatePipeline()
            if errors:
                refusals.append(f"{label}.{name}")
                check(any(name in message for message in errors),
                      f"{label}.{name} = {value}: the refusal names {name} (got: {errors[0][-160:]!r})")
                Delete(proxy)
                continue
            bad = non_finite_array(proxy)
            check(bad is None, f"{label}.{name} = {value}: refused or finite (non-finite {bad})")
            Delete(proxy)


volume = OpalVolume(**SMALL)  # noqa: F821 (from the plugin)
sweep(lambda: OpalVolume(**SMALL), "OpalVolume")  # noqa: F821
sweep(lambda: OpalSpectralRender(Input=volume, ImageSize=[16, 12]), "OpalSpectralRender")  # noqa: F821
sweep(lambda: OpalBraggMap(Input=volume), "OpalBraggMap")  # noqa: F821
check(len(refusals) > 50, f"many hostile values are refused by the filters themselves ({len(refusals)})")
print(f"{len(refusals)} refusals, each naming its property")
finish("TestOpalPropertySweep")
