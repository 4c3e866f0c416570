"""pvbatch helper: reads an opal volume from a file with ParaView's reader
(each rank reads its piece of a .pvti), renders it and saves the image (a
.pvti under MPI, one piece per rank); with --view, shows it as "Opal
Spectral" in a render view instead and saves a screenshot (OUTPUT.png; run
under Xvfb). With --pieces-of VTI each rank first checks that it read only its
piece (under MPI: fewer points than the grid's) and that the piece equals that
extent of the one-file volume VTI, before the render and after it, and that
the reader never read more than a piece meanwhile (the render and the
representation ask each rank for its piece alone). With --share-march the
view's ranks march its frames together (the representation's ShareMarch),
a still frame and then two previews (each rank with its own frame budget),
and each rank says how many marched the last preview together and its scale
("view march shared by N rank(s), preview scale S"); then the still frame
unshared (OUTPUT-unshared.png) and shared again (OUTPUT-again.png).
Usage: pvbatch opal_render_file.py INPUT OUTPUT WIDTH HEIGHT [--view [--share-march]] [--pieces-of VTI]"""
import sys

import numpy
from paraview.simple import CreateView, LoadPlugin, OpenDataFile, Render, SaveData, SaveScreenshot, Show
from vtkmodules.numpy_interface import dataset_adapter
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import opal_test_config as config


def check_piece(piece, whole_path):
    """Every array of the rank's piece equals the same extent of the whole volume."""
    reader = vtkXMLImageDataReader()
    reader.SetFileName(whole_path)
    reader.Update()
    whole = reader.GetOutput()
    controller = vtkMultiProcessController.GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    extent, points = piece.GetExtent(), piece.GetNumberOfPoints()
    print(f"rank {rank} of {ranks} read extent {extent}: {points} of {whole.GetNumberOfPoints()} points", flush=True)
    if ranks > 1 and not 0 < points < whole.GetNumberOfPoints():
        sys.exit(f"rank {rank} read {points} points, not a piece of the {whole.GetNumberOfPoints()}")
    dims = [extent[2 * a + 1] - extent[2 * a] + 1 for a in range(3)]
    for name in dataset_adapter.WrapDataObject(whole).PointData.keys():
        full = dataset_adapter.WrapDataObject(whole).PointData[name]
        full = numpy.asarray(full).reshape(whole.GetDimensions()[::-1] + (-1,))
        ours = numpy.asarray(dataset_adapter.WrapDataObject(piece).PointData[name]).reshape(dims[::-1] + [-1])
        expected = full[extent[4]:extent[5] + 1, extent[2]:extent[3] + 1, extent[0]:extent[1] + 1]
        if not numpy.array_equal(ours, expected):
            sys.exit(f"rank {rank}: {name} of its piece differs from the one-file volume")


def watch_reads(reader):
    """The points of each piece the reader reads from now on (what the render
    or the representation asked for)."""
    reads = []
    reader.AddObserver("EndEvent", lambda caller, event: reads.append(caller.GetOutputDataObject(0).GetNumberOfPoints()))
    return reads


def check_reads(reads, whole_path):
    """Under MPI no read since watch_reads was of the whole volume."""
    reader = vtkXMLImageDataReader()
    reader.SetFileName(whole_path)
    reader.UpdateInformation()
    extent = reader.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT())
    whole = (extent[1] - extent[0] + 1) * (extent[3] - extent[2] + 1) * (extent[5] - extent[4] + 1)
    controller = vtkMultiProcessController.GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    print(f"rank {rank} of {ranks} read pieces of {reads} points", flush=True)
    if ranks > 1 and not all(0 < points < whole for points in reads):
        sys.exit(f"rank {rank} read {max(reads)} points, not a piece of the {whole}")


source_path, output = sys.argv[1], sys.argv[2]
size = [int(v) for v in sys.argv[3:5]]
pieces_of = sys.argv[sys.argv.index("--pieces-of") + 1] if "--pieces-of" in sys.argv else None
LoadPlugin(config.PLUGIN, remote=True, ns=globals())
volume = OpenDataFile(source_path)
if pieces_of:
    volume.UpdatePipeline()
    check_piece(volume.GetClientSideObject().GetOutputDataObject(0), pieces_of)
    reads = watch_reads(volume.GetClientSideObject())
if "--view" in sys.argv:
    view = CreateView("RenderView")
    view.ViewSize = size
    display = Show(volume, view)
    display.Representation = "Opal Spectral"
    display.ShareMarch = int("--share-march" in sys.argv)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 40, 0], [0, 2, 0], [0, 0, -1]
    Render(view)
    SaveScreenshot(output, view, ImageResolution=size)
    if "--share-march" in sys.argv:
        # Previews (as while the view is dragged), each rank with its own
        # budget: the first preview's scale is fixed, the next follows each
        # rank's measured cost, so unagreed the ranks' scales would differ.
        display.FrameBudget = 10 if vtkMultiProcessController.GetGlobalController().GetLocalProcessId() == 0 else 0.001
        view.InteractiveRender()
        view.InteractiveRender()
        display.UpdatePropertyInformation()
        shares = display.GetProperty("LastMarchShares").GetElement(0)
        scale = display.GetProperty("LastPreviewScale").GetElement(0)
        # One write: the ranks' lines interleave.
        print(f"view march shared by {shares} rank(s), preview scale {scale}\n", end="", flush=True)
        # Unshared, then shared again: each still frame's screenshot.
        for share, name in ((0, "-unshared.png"), (1, "-again.png")):
            display.ShareMarch = share
            Render(view)
            SaveScreenshot(output[:-4] + name, view, ImageResolution=size)
else:
    render = OpalSpectralRender(Input=volume, ImageSize=size)  # noqa: F821 (from the plugin)
    SaveData(output, proxy=render, DataMode="Binary")
if pieces_of:
    # The render (or representation) asked each rank for its piece alone (and gathered what it reads).
    check_piece(volume.GetClientSideObject().GetOutputDataObject(0), pieces_of)
    check_reads(reads, pieces_of)
