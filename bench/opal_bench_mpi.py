"""Scaling bench under MPI (run with `mpiexec -np N pvbatch --symmetric`):
builds the opal volume (each rank its piece) and renders the 640 x 480 frame
(each rank its piece of the image, from the whole volume), printing per rank
the wall time of each and the peak resident memory. A run whose ranks would
together need more than this machine's memory (every rank holds the whole
volume: ~125 bytes per voxel, measured at 320 x 160 x 400) is skipped, saying so.
Usage: opal_bench_mpi.py PLUGIN NX NY NZ"""
import os
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
BYTES_PER_VOXEL = 125
per_rank = dimensions[0] * dimensions[1] * dimensions[2] * BYTES_PER_VOXEL
machine = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
if ranks * per_rank > 0.9 * machine:
    if rank == 0:
        print(f"  {dimensions[0]}x{dimensions[1]}x{dimensions[2]} voxels on {ranks} rank(s): skipped, "
              f"~{per_rank / 2**30:.1f} GB per rank (each holds the whole volume) x {ranks} exceeds "
              f"0.9 of this machine's {machine / 2**30:.1f} GB", flush=True)
    sys.exit(0)

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
