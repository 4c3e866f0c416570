"""pvpython: independent colorimetry. The Spectrum the renderer outputs,
converted by the colour-science package (CIE 1931 2-degree observer, its own
tables and integration), gives the renderer's XYZ and linear sRGB (Radiance)
within 0.5%. Rendered at 1 nm steps, where the renderer's bin-averaged
colour-matching functions and colour-science's point values coincide."""
import warnings

import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin
from vtkmodules.util.numpy_support import vtk_to_numpy

import opal_test_config as config
from opal_test_support import check, finish

warnings.filterwarnings("ignore")  # colour-science's notes about optional packages
import colour  # noqa: E402

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
volume = OpalVolume(Preset="fig15", Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821
render = OpalSpectralRender(Input=volume, ImageSize=[24, 18], WavelengthStep=1.0, WriteSpectrum=1)  # noqa: F821
render.UpdatePipeline()
image = sm.Fetch(render)
pd = image.GetPointData()
spectra = vtk_to_numpy(pd.GetArray("Spectrum"))
xyz = vtk_to_numpy(pd.GetArray("XYZ"))
radiance = vtk_to_numpy(pd.GetArray("Radiance"))
lambdas = vtk_to_numpy(image.GetFieldData().GetArray("Wavelengths"))

cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
tables = numpy.array(cmfs[lambdas])  # x-bar, y-bar, z-bar at each wavelength
step = lambdas[1] - lambdas[0]


lit = numpy.nonzero(xyz[:, 1] > 0.02 * xyz[:, 1].max())[0]
check(len(lit) > 50, f"many lit pixels to compare ({len(lit)})")
worst_xyz = worst_rgb = 0.0
for pixel in lit:
    # XYZ = sum S(lambda) xbar(lambda) dlambda over colour-science's own CIE tables.
    reference = step * spectra[pixel].astype(float) @ tables
    rgb = colour.XYZ_to_sRGB(reference, apply_cctf_encoding=False)
    scale = max(abs(reference).max(), 1e-12)
    worst_xyz = max(worst_xyz, abs(xyz[pixel] - reference).max() / scale)
    worst_rgb = max(worst_rgb, abs(radiance[pixel] - rgb).max() / max(abs(rgb).max(), 1e-12))
print(f"worst XYZ difference {100 * worst_xyz:.3f}%, worst linear sRGB difference {100 * worst_rgb:.3f}%")
check(worst_xyz < 0.005, "XYZ within 0.5% of colour-science")
check(worst_rgb < 0.005, "linear sRGB (Radiance) within 0.5% of colour-science")
finish("TestOpalColourScience")
