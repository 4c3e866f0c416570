"""pvpython and opal-render: ScatteringOrders (docs/design.md §3.10) takes the
volume's by default (single for the paper's figures, all for the kinds of
opal and a custom volume, also for a volume saved and read back), a value set
is used as set, the image's field data records what was rendered, every order
brightens the body (more in the blue), and a value other than single/all is
refused naming it (in ParaView by its enumeration, on the command line by
its flag, exit 2)."""
import os
import subprocess

import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin, SaveData, XMLImageDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import opal_test_config as config
from opal_test_support import check, finish, run

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
small = dict(Dimensions=[40, 20, 50], DomainCount=30)
size = dict(ImageSize=[48, 36], Exposure=1.0)


def rendered(render):
    image = sm.Fetch(render)
    orders = image.GetFieldData().GetAbstractArray("ScatteringOrders").GetValue(0)
    return orders, vtk_to_numpy(image.GetPointData().GetArray("XYZ")).copy()


fig12 = OpalVolume(Preset="fig12", **small)  # noqa: F821 (from the plugin)
white = OpalVolume(Preset="white-opal", **small)  # noqa: F821
custom = OpalVolume(Preset="custom", **small)  # noqa: F821
check(rendered(OpalSpectralRender(Input=fig12, **size))[0] == "single", "fig12 renders single scattering by default")  # noqa: F821
orders, white_all = rendered(OpalSpectralRender(Input=white, **size))  # noqa: F821
check(orders == "all", "white-opal renders every order by default")
check(rendered(OpalSpectralRender(Input=custom, **size))[0] == "all", "a custom volume renders every order by default")  # noqa: F821
orders, white_single = rendered(OpalSpectralRender(Input=white, ScatteringOrders="single", **size))  # noqa: F821
check(orders == "single", "single set on white-opal is used")
gain = white_all.sum(axis=0) / white_single.sum(axis=0)
check(numpy.all(numpy.isfinite(white_all)) and gain[2] > gain[0] > 1.1,
      f"every order brightens the body, the blue (Z) most: X, Y, Z x{gain[0]:.2f} x{gain[1]:.2f} x{gain[2]:.2f}")
check(rendered(OpalSpectralRender(Input=fig12, ScatteringOrders="all", **size))[0] == "all",  # noqa: F821
      "all set on fig12 is used")

path = os.path.join(config.OUTPUT_DIRECTORY, "TestOpalScatteringOrders-white.vti")
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
SaveData(path, proxy=white, DataMode="Binary")
check(rendered(OpalSpectralRender(Input=XMLImageDataReader(FileName=[path]), **size))[0] == "all",  # noqa: F821
      "a saved white-opal volume renders every order by default")

# The command line: the same defaults, the flag, and a refusal naming the parameter.
common = [config.OPAL_RENDER, "--dimensions", "40", "20", "50", "--domain-count", "30", "--image-size", "48", "36"]
for preset, flag, expected in (("fig12", [], "single"), ("white-opal", [], "all"), ("fig12", ["--scattering-orders", "all"], "all")):
    out = os.path.join(config.OUTPUT_DIRECTORY, f"TestOpalScatteringOrders-{preset}-{expected}.vti")
    run(common + ["--preset", preset, "--save-image", out] + flag)
    reader = vtkXMLImageDataReader()
    reader.SetFileName(out)
    reader.Update()
    got = reader.GetOutput().GetFieldData().GetAbstractArray("ScatteringOrders").GetValue(0)
    check(got == expected, f"opal-render --preset {preset} {' '.join(flag)} renders {expected}: {got}")
refused = subprocess.run(common + ["--scattering-orders", "3", "-o", os.path.join(config.OUTPUT_DIRECTORY, "x.png")],
                         capture_output=True, text=True)
check(refused.returncode == 2 and "--scattering-orders" in refused.stderr,
      f"--scattering-orders 3 is refused naming the flag, exit 2: {refused.stderr.strip()}")
finish("TestOpalScatteringOrders")
