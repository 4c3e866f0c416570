"""pvbatch --symmetric helper: every rank renders a small opal, rank 1 with
`StepSize` 0.5 in the settings case, a bad `ViewAngle` in the information
case. Each rank then prints whether it holds an image piece ("rank R image
POINTS"), so the driver sees that none holds part of a failed image.
Usage: mpiexec -np N pvbatch --symmetric opal_rank_agreement_scene.py same|settings|information"""
import sys

from paraview.simple import LoadPlugin
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import opal_test_config as config

case = sys.argv[1]
LoadPlugin(config.PLUGIN, remote=False, ns=globals())
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30)  # noqa: F821 (from the plugin)
render = OpalSpectralRender(Input=volume, ImageSize=[48, 36])  # noqa: F821
if rank == 1 and case == "settings":
    render.StepSize = 0.5
if rank == 1 and case == "information":
    render.ViewAngle = 200
render.UpdatePipeline()
image = render.GetClientSideObject().GetOutputDataObject(0)
print(f"rank {rank} image {image.GetNumberOfPoints()}", flush=True)
