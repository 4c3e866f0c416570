"""pvbatch --symmetric helper: every rank renders a small opal, rank 1 with
`StepSize` 0.5 in the settings case, a bad `ViewAngle` in the information
case; with every order of scattering in the every-order case, and in the
abort case with rank 1 asking to abort at its first progress above 0.1
(past the ranks' shared light field, inside their shared photon solve); in
the above-abort case with rank 1 asking to abort at its first progress above
0 (inside the ranks' sweep of the light from above); in the side case the
light low to the side (the ranks share its march from every voxel), and in
the side-abort case with rank 1 asking to abort at its first progress above
0 (inside that march); in the voronoi case the volume's layout is of
Voronoi grains, and in the voronoi-abort case rank 1's volume then asks to
abort at its first progress above 0 (inside the ranks' shared assignment of
the cells); in the march case the ranks march the view rays together
(ShareMarch), and in the march-abort case rank 1 then asks to abort at its
first progress above 0.3 (inside the shared march of the image, past the
exposure's thumbnail); in the absent case rank 1 never updates the render
(as where it stopped, or went on elsewhere) and every rank bounds its waits in
an exchange to 5 s (OPAL_EXCHANGE_WAIT_LIMIT). Each rank then prints whether it holds an image piece
and how many ranks traced its every-order field, computed its light field,
assigned its volume's cells and marched its view rays ("rank R image POINTS
shares S light L cells C march M"), so the driver sees that none holds part
of a failed image.
Usage: mpiexec -np N pvbatch --symmetric opal_rank_agreement_scene.py same|settings|information|every-order|abort|
       above-abort|side|side-abort|voronoi|voronoi-abort|march|march-abort|absent"""
import os
import sys
import time

from paraview.simple import LoadPlugin
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import opal_test_config as config

case = sys.argv[1]
LoadPlugin(config.PLUGIN, remote=False, ns=globals())
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821 (from the plugin)
if case in ("voronoi", "voronoi-abort"):
    volume.DomainLayout = "voronoi"
if case == "voronoi-abort" and rank == 1:
    volume.GetClientSideObject().AddObserver(
        "ProgressEvent", lambda source, _: source.GetProgress() > 0 and source.SetAbortExecute(1))
render = OpalSpectralRender(Input=volume, ImageSize=[48, 36])  # noqa: F821
if case in ("every-order", "abort"):
    render.ScatteringOrders = "all"
if case in ("side", "side-abort"):
    render.LightPosition = [60, 10, 0]
if case in ("march", "march-abort"):
    render.ShareMarch = 1
if rank == 1 and case in ("abort", "above-abort", "side-abort", "march-abort"):
    # The request's own start reports 0; with every order, the shared light
    # field's last progress 0.1; the image's march starts at 0.25 (docs/design.md §8.1).
    after = {"abort": 0.1, "march-abort": 0.3}.get(case, 0.0)
    render.GetClientSideObject().AddObserver(
        "ProgressEvent", lambda filter, _: filter.GetProgress() > after and filter.SetAbortExecute(1))
if rank == 1 and case == "settings":
    render.StepSize = 0.5
if rank == 1 and case == "information":
    render.ViewAngle = 200
if case == "absent":
    os.environ["OPAL_EXCHANGE_WAIT_LIMIT"] = "5"
    if rank == 1:
        # Not an exit: mpiexec would end the job for it (pvbatch leaves without
        # MPI's finalize), which no bound is needed for.
        print("rank 1 never renders", flush=True)
        time.sleep(120)
        sys.exit(0)
render.UpdatePipeline()
image = render.GetClientSideObject().GetOutputDataObject(0)
render.UpdatePropertyInformation()
shares = render.GetProperty("LastScatteredLightShares").GetElement(0)
light = render.GetProperty("LastLightFieldShares").GetElement(0)
volume.UpdatePropertyInformation()
cells = volume.GetProperty("LastVoronoiCellShares").GetElement(0)
march = render.GetProperty("LastMarchShares").GetElement(0)
print(f"rank {rank} image {image.GetNumberOfPoints()} shares {shares} light {light} cells {cells} march {march}",
      flush=True)
