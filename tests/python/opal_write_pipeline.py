"""pvbatch helper: builds an Opal Volume, optionally renders it, and saves the
result (a .pvti under MPI, one piece per rank). With --voronoi the volume is
of Voronoi grains with correlated scattering diameters; --preset NAME starts
from a preset (its grid replaced by the one given; the render takes the
preset's Bragg model and planes); --side-light puts the light low to the side
(the per-voxel light march instead of the sweep from above); --share-march
has the ranks march the view rays together, each through its piece of the
volume's layers (ShareMarch); --again renders
once more with a new device session, which holds no volume (under MPI the
render gathers the arrays it released after the first upload), into
OUTPUT-again.pvti; --unshared-again renders once more with ShareMarch off
(each rank's device held only its piece of the medium: the ranks gather the
volume again and upload it whole) into the same file.
Usage: pvbatch opal_write_pipeline.py OUTPUT NX NY NZ [WIDTH HEIGHT] [--voronoi] [--preset NAME] [--side-light]
       [--share-march] [--again | --unshared-again]"""
import sys

from paraview.simple import LoadPlugin, SaveData

import opal_test_config as config

arguments = list(sys.argv)
voronoi = "--voronoi" in arguments
side_light = "--side-light" in arguments
again = "--again" in arguments
unshared_again = "--unshared-again" in arguments
share_march = "--share-march" in arguments
preset = {}
if "--preset" in arguments:
    at = arguments.index("--preset")
    preset = dict(Preset=arguments[at + 1])
    del arguments[at:at + 2]
arguments = [a for a in arguments if a not in ("--voronoi", "--side-light", "--share-march", "--again", "--unshared-again")]
output, dimensions = arguments[1], [int(v) for v in arguments[2:5]]
LoadPlugin(config.PLUGIN, remote=True, ns=globals())
grains = dict(DomainLayout="voronoi", VoronoiCellCount=150, DiameterCorrelationLength=0.8) if voronoi else {}
# A preset first, then the grid (and domains) given: an edit wins over the preset's value.
volume = result = OpalVolume(**preset, Dimensions=dimensions, **({} if preset else dict(DomainCount=60)), **grains)  # noqa: F821
if len(arguments) > 6:
    light = dict(LightPosition=[60, 10, 0]) if side_light else {}
    result = OpalSpectralRender(Input=result, ImageSize=[int(v) for v in arguments[5:7]], ShareMarch=share_march,  # noqa: F821
                                **light)
# Inline binary: Debian's VTK 9.2 with its patched expat cannot read appended XML data.
SaveData(output, proxy=result, DataMode="Binary")
volume.UpdatePropertyInformation()
print("Voronoi cells assigned by", volume.GetProperty("LastVoronoiCellShares").GetElement(0), "rank(s)")
if len(arguments) > 6:
    result.UpdatePropertyInformation()
    print("every-order field traced by", result.GetProperty("LastScatteredLightShares").GetElement(0), "rank(s)")
    print("light field computed by", result.GetProperty("LastLightFieldShares").GetElement(0), "rank(s)")
    print("view march shared by", result.GetProperty("LastMarchShares").GetElement(0), "rank(s)")
    for what, name in (("gathered", "LastGatheredLayers"), ("held on the device", "LastMediumLayers")):
        layers = result.GetProperty(name)
        print(f"medium {what} for layers", layers.GetElement(0), "to", layers.GetElement(1))
if again or unshared_again:
    if again:
        result.DeviceMemoryLimit = 16000  # MB: a new session
    else:
        result.ShareMarch = 0
    SaveData(output.replace(".pvti", "-again.pvti"), proxy=result, DataMode="Binary")
