"""pvbatch helper: builds an Opal Volume, optionally renders it, and saves the
result (a .pvti under MPI, one piece per rank).
Usage: pvbatch opal_write_pipeline.py OUTPUT NX NY NZ [WIDTH HEIGHT]"""
import sys

from paraview.simple import LoadPlugin, SaveData

import opal_test_config as config

output, dimensions = sys.argv[1], [int(v) for v in sys.argv[2:5]]
LoadPlugin(config.PLUGIN, remote=True, ns=globals())
result = OpalVolume(Dimensions=dimensions, DomainCount=60)  # noqa: F821 (from the plugin)
if len(sys.argv) > 6:
    result = OpalSpectralRender(Input=result, ImageSize=[int(v) for v in sys.argv[5:7]])  # noqa: F821
# Inline binary: Debian's VTK 9.2 with its patched expat cannot read appended XML data.
SaveData(output, proxy=result, DataMode="Binary")
