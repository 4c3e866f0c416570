"""Scaling bench under MPI (run with `mpiexec -np N pvbatch --symmetric`):
builds the opal volume (each rank its piece) and renders the 640 x 480 frame
(each rank its piece of the image, from the whole volume), printing per rank
the wall time of each and the peak resident memory.
Usage: opal_bench_mpi.py PLUGIN NX NY NZ"""
import resource
import sys
import time

from paraview.simple import LoadPlugin
from paraview import servermanager
from vtkmodules.vtkParallelCore import vtkMultiProcessController

plugin, dimensions = sys.argv[1], [int(v) for v in sys.argv[2:5]]
LoadPlugin(plugin, remote=False, ns=globals())
controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

volume = OpalVolume(Dimensions=dimensions)  # noqa: F821 (from the plugin)
controller.Barrier()
start = time.perf_counter()
volume.UpdatePipeline(0.0)
volume_seconds = time.perf_counter() - start
render = OpalSpectralRender(Input=volume)  # noqa: F821
controller.Barrier()
start = time.perf_counter()
render.UpdatePipeline(0.0)
render_seconds = time.perf_counter() - start
controller.Barrier()
peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
for r in range(ranks):
    if r == rank:
        print(f"  {dimensions[0]}x{dimensions[1]}x{dimensions[2]} voxels, rank {rank} of {ranks}: "
              f"volume piece {volume_seconds:.3f} s, render (whole volume + its image piece) "
              f"{render_seconds:.3f} s, peak memory {peak_mb:.0f} MB", flush=True)
    controller.Barrier()
