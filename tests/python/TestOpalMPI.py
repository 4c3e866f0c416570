"""pvpython: `mpiexec -np N pvbatch` builds the opal volume (and renders it) as
N pieces, one per rank, and the result equals the one-process run.

Volume: every array exactly. Render: each rank builds its piece of the volume,
the ranks gather the arrays the render reads into the whole volume on every
rank, and each renders its rows and columns of the image from it with the same
automatic exposure (taken from a thumbnail of the whole image), so RGB must
match exactly and the float arrays to 1e-5 relative (identical arithmetic; the
tolerance only allows for a different CPU path).
The voronoi case is the volume of Voronoi grains with correlated diameters
(CellId too). The grains case renders the pinfire preset's grains; the fire
case the fire-opal preset (an absorbing body, coupled-wave fcc, every order)
lit low from the side, its light field's march from every voxel and its
every-order photon solve shared by the ranks. The march, fire-march and
thin-march (fig12 on 12 layers, which some ranks' pieces and halos span) cases
render fig12 and fire-opal with ShareMarch: each rank marches the view rays
only through its piece of the volume's layers, handing them to the others,
each rank's device holding only its piece of the medium, and every rank
renders the whole image and keeps its piece: the same image; the march case
then renders unshared, the volume gathered and uploaded whole again.
The pvti case reads the volume from a partitioned file, each rank its piece,
and renders it; the view case shows that file as "Opal Spectral" in a render
view (the live view's representation), each rank again asking for its piece
alone, and the screenshot equals the one-process one; the view-march case
likewise with the representation's ShareMarch (a still frame, then
previews with each rank's own frame budget), every rank saying that the
ranks marched the preview together at one scale, and the still frame equals
the one-process one shared, unshared and shared again.
Usage: pvpython TestOpalMPI.py N volume|voronoi|render|grains|fire|march|fire-march|thin-march|pvti|view|view-march"""
import os
import re
import sys

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader

import opal_test_config as config
from opal_test_support import check, finish, on_virtual_display, run

ranks, kind = int(sys.argv[1]), sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
serial = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_serial.vti")
parallel = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_parallel.pvti")
mpiexec = [config.MPIEXEC, "-np", str(ranks), config.PVBATCH]

views = ("view", "view-march")
if kind in ("pvti",) + views:
    # A volume file read by pieces: opal-volume writes it as one .vti and as a
    # .pvti of 4 pieces; each rank reads only its piece of the .pvti (checked
    # against the .vti), the render or the view asks for no more (checked
    # after it), and the image of the pieces equals the one-process image of the .vti.
    reader = os.path.join(here, "opal_render_file.py")
    whole = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_volume.vti")
    pieces = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_volume.pvti")
    volume = [config.OPAL_VOLUME, "--dimensions", "48", "24", "60", "--domain-count", "60"]
    run(volume + ["-o", whole])
    written = run(volume + ["-o", pieces, "--pieces", "4"]).stdout
    check("(4 pieces)" in written, "opal-volume says it wrote 4 pieces")
    view = ["--view"] + (["--share-march"] if kind == "view-march" else []) if kind in views else []
    if view:
        serial, parallel = serial[:-4] + ".png", parallel[:-5] + ".png"

    def display(command):
        """The views need a display."""
        return on_virtual_display(command, "640x480x24") if view else command

    run(display([config.PVBATCH, reader, whole, serial, "96", "72"] + view))
    read_by_ranks = run(display(mpiexec[:-1] + [config.PVBATCH, "--symmetric", reader, pieces, parallel, "96", "72",
                                                "--pieces-of", whole] + view)).stdout
    check(read_by_ranks.count(" read extent ") == 2 * ranks,
          f"each of the {ranks} ranks read its own piece, before the render and after it:\n" + read_by_ranks)
    if kind == "view-march":
        said = re.findall(r"view march shared by (\d+) rank\(s\), preview scale (\d+)", read_by_ranks)
        check(len(said) == ranks and all(int(shares) == ranks for shares, _ in said),
              f"every rank's view marched its preview with the {ranks} ranks together:\n" + read_by_ranks)
        check(len({scale for _, scale in said}) == 1 and int(said[0][1]) > 1,
              f"the ranks' previews took one scale, the coarsest of their budgets':\n" + read_by_ranks)
else:
    fire = ["--preset", "fire-opal", "--side-light"]
    renders = {"render": [], "grains": ["--preset", "pinfire"], "fire": fire,
               "march": ["--share-march"], "fire-march": fire + ["--share-march"], "thin-march": ["--share-march"]}
    grid = ["16", "8", "12"] if kind == "thin-march" else ["48", "24", "60"]
    arguments = grid + (["96", "72"] + renders[kind] if kind in renders else []) + \
        (["--voronoi"] if kind == "voronoi" else [])
    writer = os.path.join(here, "opal_write_pipeline.py")
    alone = run([config.PVBATCH, writer, serial] + arguments).stdout
    again = {"render": ["--again"], "march": ["--unshared-again"]}
    together = run(mpiexec + [writer, parallel] + arguments + again.get(kind, [])).stdout
    if kind in ("voronoi", "grains"):
        # The ranks share the Voronoi cells' assignment (each a share of the
        # grid's layers, docs/design.md §8.1); the volume stays exact (below).
        check("Voronoi cells assigned by 1 rank(s)" in alone, "one process assigns the cells alone:\n" + alone)
        check(f"Voronoi cells assigned by {ranks} rank(s)" in together,
              f"the {ranks} ranks share the Voronoi cells:\n" + together)
    if kind.endswith("march"):
        # The ranks march the view rays together (docs/design.md §8.1).
        check("view march shared by 0 rank(s)" in alone, "one process marches alone:\n" + alone)
        check(f"view march shared by {ranks} rank(s)" in together,
              f"the {ranks} ranks march the view rays together:\n" + together)
        # Rank 0's host gathered the medium's arrays (all but SurfaceDistance)
        # for its piece of the 60 layers and 7 beside it, and its device held
        # its cells and SurfaceDistance for the piece and 6 beside it
        # (docs/design.md §8.1); one process holds all of them.
        layers = int(grid[2])
        piece = layers // ranks
        for what, alone_layers, rank0_layers in (("gathered", layers, piece + 7), ("held on the device", layers, piece + 6)):
            check(f"medium {what} for layers 0 to {alone_layers}" in alone, f"one process's medium {what} whole:\n" + alone)
            check(f"medium {what} for layers 0 to {rank0_layers}" in together,
                  f"rank 0's medium {what} for its piece of {ranks}:\n" + together)
    if kind.startswith("fire"):
        # Every order: the ranks share the photon solve (each traces a share,
        # all build the field from every share's scores, docs/design.md §8.1).
        check("every-order field traced by 1 rank(s)" in alone, "one process solves the every-order field alone:\n" + alone)
        check(f"every-order field traced by {ranks} rank(s)" in together,
              f"the {ranks} ranks share the every-order solve:\n" + together)
    if kind in renders:
        # The ranks share the light field (each a share of the layers' rows,
        # docs/design.md §8.1): marched from every voxel with the light low to
        # the side (fire), swept layer after layer with it above (render, grains).
        check("light field computed by 1 rank(s)" in alone, "one process computes the light field alone:\n" + alone)
        check(f"light field computed by {ranks} rank(s)" in together,
              f"the {ranks} ranks share the light field:\n" + together)


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    return reader


if kind in views:
    # With ShareMarch, the still frame then unshared and shared again.
    again = [parallel[:-4] + name for name in ("-unshared.png", "-again.png")] if kind == "view-march" else []
    images = [vtk_to_numpy(read(vtkPNGReader, path).GetOutput().GetPointData().GetScalars())
              for path in [serial, parallel] + again]
    stone = numpy.mean(numpy.any(images[0] != images[0][0], axis=1))
    check(0.1 < stone < 0.9, f"the one-process view shows the stone ({100 * stone:.0f}% of the view)")
    # Each rank renders the whole stone from the same gathered volume, and
    # ParaView composites equal frames by depth: the screenshots are equal.
    for path, image in zip([parallel] + again, images[1:]):
        differing = numpy.mean(numpy.any(images[0] != image, axis=1))
        check(images[0].shape == image.shape and differing == 0,
              f"the {ranks}-rank view {os.path.basename(path)} equals the one-process view "
              f"({100 * differing:.2f}% of pixels differ)")
    finish("TestOpalMPI", f"({kind}, {ranks} ranks)")
serial_data = read(vtkXMLImageDataReader, serial).GetOutput()
parallel_reader = read(vtkXMLPImageDataReader, parallel)
parallel_data = parallel_reader.GetOutput()


check(parallel_reader.GetNumberOfPieces() == ranks,
      f"{ranks} pieces written, got {parallel_reader.GetNumberOfPieces()}")
check(serial_data.GetDimensions() == parallel_data.GetDimensions(), "same grid")
if kind in ("volume", "voronoi"):
    exact = ["VoxelType", "ParticleDiameter", "Normal", "DomainId", "BraggLambdaMax",
             "BraggLambdaMin", "ScatteringCoefficient", "SurfaceDistance", "LatticeOrientation"] + (["CellId"] if kind == "voronoi" else [])
    close = []
else:
    exact = ["RGB"]
    close = ["Radiance", "XYZ", "DominantBraggWavelength", "Depth"]
if kind in ("render", "march"):
    # A new device session after the render, or the march unshared after the
    # shared one (each rank's device held only its piece of the medium): the
    # ranks gather the arrays they released after the first upload again
    # (docs/design.md §8.1), and render the same image.
    again_data = read(vtkXMLPImageDataReader, parallel.replace(".pvti", "-again.pvti")).GetOutput()
    again_rgb = again_data.GetPointData().GetArray("RGB")
    check(again_rgb is not None and numpy.array_equal(vtk_to_numpy(again_rgb),
                                                      vtk_to_numpy(parallel_data.GetPointData().GetArray("RGB"))),
          "rendered again on a new device session, or unshared, the ranks' image is the same")
for name in exact + close:
    a = serial_data.GetPointData().GetArray(name)
    b = parallel_data.GetPointData().GetArray(name)
    check(a is not None and b is not None, f"{name} present in both")
    if a is None or b is None:
        continue
    a, b = vtk_to_numpy(a), vtk_to_numpy(b)
    if name in exact:
        check(numpy.array_equal(a, b), f"{name}: {ranks}-rank result equals the one-process result")
    else:
        check(numpy.allclose(a, b, rtol=1e-5, atol=1e-7),
              f"{name}: {ranks}-rank result within 1e-5 of one process "
              f"(largest difference {numpy.max(numpy.abs(a - b))})")
finish("TestOpalMPI", f"({kind}, {ranks} ranks)")
