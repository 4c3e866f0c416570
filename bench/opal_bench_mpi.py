"""Scaling bench under MPI (run with `mpiexec -np N pvbatch --symmetric`):
builds the opal volume (each rank its piece) and renders the 640 x 480 frame
(each rank its piece of the image, from the whole volume), then again with
every order of scattering (the ranks sharing its photon solve) and with the
light low to the side (the ranks sharing its march from every voxel) and
with the view march shared by the ranks (ShareMarch), printing per rank
the wall time of each, the render's stages (gather, upload, light pass,
every-order solve, march and its rounds of exchange, the rest) and the peak resident memory with the
render session's peak of device buffers (host memory on lavapipe), and from rank 0's
figures an estimate for the 10 um stone (16 x 8 x 20 mm, 1600 x 800 x 2000
voxels). The estimate's bytes per voxel are the peak's beyond the process's
own footprint, which a volume of a few voxels rendered first measures
(pvbatch, the Vulkan device and its pipelines, the image: ~0.5 GB on lavapipe
whatever the volume), so that they are not spread over the voxels. A run
whose ranks would together need more than this machine's memory is skipped,
saying so: each rank holds its piece of the volume's arrays and the device fields of the whole volume (and the gathered arrays
until their upload), ~54 / ranks + 64 bytes per voxel (fitted to 320 x 160 x
400 on 1, 2 and 4 ranks, the process included; 13 / ranks with the render's
arrays). ARRAYS is the volume's OutputArrays: all (the default) or render
(only what the render reads). SCHEME is whole (the default: each rank
renders its piece of the image from the whole volume's fields, then the
shared steps above) or pieces: every render, the footprint's too, with
ShareMarch (each rank's device holding its piece of the light fields, the
every-order field and the medium: its cells and SurfaceDistance), the frame
then every order, and the estimate from it.
Usage: opal_bench_mpi.py PLUGIN NX NY NZ [ARRAYS [SCHEME]]"""
import os
import resource
import sys
import time

from paraview.simple import Delete, LoadPlugin
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController

plugin, dimensions = sys.argv[1], [int(v) for v in sys.argv[2:5]]
arrays = sys.argv[5] if len(sys.argv) > 5 else "all"
pieces = len(sys.argv) > 6 and sys.argv[6] == "pieces"
LoadPlugin(plugin, remote=False, ns=globals())
controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
PIECE_BYTES, WHOLE_BYTES = (54 if arrays == "all" else 13), 64
voxels = dimensions[0] * dimensions[1] * dimensions[2]
size = (f"{dimensions[0]}x{dimensions[1]}x{dimensions[2]} voxels" + (", render arrays" if arrays == "render" else "") +
        (", ShareMarch" if pieces else ""))


def fits():
    """Whether the ranks' estimated memory fits this machine; else says so (rank 0)."""
    per_rank = voxels * (PIECE_BYTES / ranks + WHOLE_BYTES)
    machine = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    if ranks * per_rank <= 0.9 * machine:
        return True
    if rank == 0:
        print(f"  {size} on {ranks} rank(s): skipped, ~{per_rank / 2**30:.1f} GB per rank (the render's whole "
              f"volume on each) x {ranks} exceeds 0.9 of this machine's {machine / 2**30:.1f} GB", flush=True)
    return False


def timed(proxy):
    controller.Barrier()
    start = time.perf_counter()
    proxy.UpdatePipeline(0.0)
    return time.perf_counter() - start


def report(render, volume_seconds, render_seconds, peak_mb):
    """Prints each rank's figures in rank order; the device peak in MB, or
    None where the render refused (said in its error, on every rank alike)."""
    fields = render.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
    stages = fields.GetArray("RenderTimings")
    if stages is None:
        if rank == 0:
            print(f"  {size} on {ranks} rank(s): the render refused it (the error above), "
                  f"peak memory {peak_mb:.0f} MB", flush=True)
        return None
    stage = {stages.GetComponentName(c): stages.GetComponent(0, c) for c in range(stages.GetNumberOfComponents())}
    device_mb = fields.GetArray("DeviceMemoryPeak").GetValue(0) / 2**20
    render.UpdatePropertyInformation()
    gather = render.SMProxy.GetProperty("LastGatherSeconds").GetElement(0)
    # The frame's stages are the render session's; besides the gather, the
    # rest of the render's time is the Vulkan device's start, the ranks'
    # agreements and the pipeline.
    rounds = stage.pop("MarchRounds", 0.0)  # a part of the march
    other = render_seconds - gather - sum(stage.values())
    march = f"march {stage['March']:.3f}" + (f" (its rounds {rounds:.3f})" if rounds > 0 else "")
    for r in range(ranks):
        if r == rank:
            print(f"  {size}, rank {rank} of {ranks}: volume piece {volume_seconds:.3f} s, render "
                  f"{render_seconds:.3f} s (gather {gather:.3f}, upload {stage['Upload']:.3f}, light pass "
                  f"{stage['LightPass']:.3f}, every order {stage['ScatteredLight']:.3f}, {march}, "
                  f"other {other:.3f} s), peak memory {peak_mb:.0f} MB (of which device buffers "
                  f"{device_mb:.0f} MB)", flush=True)
        controller.Barrier()
    return device_mb


def process_footprint():
    """The process's peak, in MB, once it has rendered a volume of a few voxels
    (its Vulkan device started and its pipelines built); that render is then
    deleted. Its device peak too (the image's buffers)."""
    small = OpalVolume(Dimensions=[8, 4, 10], DomainCount=10, OutputArrays=arrays)  # noqa: F821 (from the plugin)
    render = OpalSpectralRender(Input=small, ShareMarch=int(pieces))  # noqa: F821
    render.UpdatePipeline(0.0)
    fields = render.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
    device = fields.GetArray("DeviceMemoryPeak")
    device_mb = device.GetValue(0) / 2**20 if device is not None else 0.0
    Delete(render)
    Delete(small)
    controller.Barrier()
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, device_mb


def estimate(volume_seconds, bytes_per_voxel, device_bytes_per_voxel):
    """The 10 um stone from this run's per-voxel costs (rank 0 prints): the
    fastest rank's volume time per voxel and rank (rank 0 also builds the
    domain polygons), and the memory per voxel beyond the process's own footprint."""
    fastest = vtkDoubleArray()
    fastest.InsertNextValue(volume_seconds)
    fastest_all = vtkDoubleArray()
    controller.AllReduce(fastest, fastest_all, vtkCommunicator.MIN_OP)
    if rank != 0:
        return
    stone = 1600 * 800 * 2000
    build_ns = fastest_all.GetValue(0) * ranks / voxels * 1e9
    print(f"  10 um estimate (1600x800x2000 = {stone / 1e9:.2f} G voxels) from this run: volume "
          f"{build_ns:.0f} ns per voxel and rank, {stone * build_ns / 1e9 / ranks:.0f} s on {ranks} rank(s); "
          f"{bytes_per_voxel:.0f} bytes per voxel here beyond the process's own footprint "
          f"({device_bytes_per_voxel:.0f} of them device buffers), so {stone * bytes_per_voxel / 2**30:.0f} GB per rank "
          + ("(each rank's device its piece of the light fields and the medium, SurfaceDistance's tiles whole; "
             "its host SurfaceDistance whole until the upload)" if pieces
             else "(the device fields of the whole volume on every rank)"), flush=True)


def shared_stage(render, heading, shares_property):
    """Renders again with the settings just changed and prints its figures
    under `heading`, given how many ranks shared the step `shares_property` counts."""
    seconds = timed(render)
    render.UpdatePropertyInformation()
    shares = render.GetProperty(shares_property).GetElement(0)
    if rank == 0:
        print("  " + heading.format(shares), flush=True)
    report(render, 0.0, seconds, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)


# No rank leaves early (pvbatch under MPI must reach its end on every rank).
if fits():
    baseline_mb, baseline_device_mb = process_footprint()
    if rank == 0:
        print(f"  the process's own footprint (a render of 8x4x10 voxels): {baseline_mb:.0f} MB "
              f"(of which device buffers {baseline_device_mb:.0f} MB)", flush=True)
    volume = OpalVolume(Dimensions=dimensions, OutputArrays=arrays)  # noqa: F821 (from the plugin)
    volume_seconds = timed(volume)
    render = OpalSpectralRender(Input=volume, ShareMarch=int(pieces))  # noqa: F821
    render_seconds = timed(render)
    controller.Barrier()
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    device_mb = report(render, volume_seconds, render_seconds, peak_mb)
    if device_mb is not None:
        estimate(volume_seconds, (peak_mb - baseline_mb) * 2**20 / voxels,
                 (device_mb - baseline_device_mb) * 2**20 / voxels)
        # Every order of scattering, the volume and its light pass kept: the
        # ranks share the photon solve (its stage, "every order").
        render.ScatteringOrders = "all"
        shared_stage(render, "every order, traced by {} rank(s):", "LastScatteredLightShares")
    if device_mb is not None and not pieces:
        # The light low to the side, single scattering: the light pass marches
        # from every voxel, and the ranks share it (its stage, "light pass").
        render.ScatteringOrders = "single"
        render.LightPosition = [60, 10, 0]
        shared_stage(render, "the light low to the side (single scattering), its field marched by {} rank(s):",
                     "LastLightFieldShares")
        # The view rays marched by the ranks together, each through its piece
        # of the layers (ShareMarch), the light field kept: its stage, "march",
        # of which the rounds' exchanges and the states' copies.
        render.ShareMarch = 1
        shared_stage(render, "the view march shared by {} rank(s):", "LastMarchShares")
