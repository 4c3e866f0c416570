"""pvbatch helper: builds an Opal Volume, optionally renders it, and saves the
result (a .pvti under MPI, one piece per rank). With --voronoi the volume is
of Voronoi grains with correlated scattering diameters.
Usage: pvbatch opal_write_pipeline.py OUTPUT NX NY NZ [WIDTH HEIGHT] [--voronoi]"""
import sys

from paraview.simple import LoadPlugin, SaveData

import opal_test_config as config

voronoi = "--voronoi" in sys.argv
arguments = [a for a in sys.argv if a != "--voronoi"]
output, dimensions = arguments[1], [int(v) for v in arguments[2:5]]
LoadPlugin(config.PLUGIN, remote=True, ns=globals())
grains = dict(DomainLayout="voronoi", VoronoiCellCount=150, DiameterCorrelationLength=0.8) if voronoi else {}
result = OpalVolume(Dimensions=dimensions, DomainCount=60, **grains)  # noqa: F821 (from the plugin)
if len(arguments) > 6:
    result = OpalSpectralRender(Input=result, ImageSize=[int(v) for v in arguments[5:7]])  # noqa: F821
# Inline binary: Debian's VTK 9.2 with its patched expat cannot read appended XML data.
SaveData(output, proxy=result, DataMode="Binary")
