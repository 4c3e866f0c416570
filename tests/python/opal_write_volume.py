"""pvbatch helper: builds an Opal Volume and saves it (a .pvti under MPI, one
piece per rank). Usage: pvbatch opal_write_volume.py OUTPUT NX NY NZ"""
import sys

from paraview.simple import LoadPlugin, SaveData

import opal_test_config as config

output, dimensions = sys.argv[1], [int(v) for v in sys.argv[2:5]]
LoadPlugin(config.PLUGIN, remote=True, ns=globals())
volume = OpalVolume(Dimensions=dimensions, DomainCount=60)  # noqa: F821 (from the plugin)
# Inline binary: Debian's VTK 9.2 with its patched expat cannot read appended XML data.
SaveData(output, proxy=volume, DataMode="Binary")
