"""pvpython: `mpiexec -np N pvbatch` builds the opal volume (and renders it) as
N pieces, one per rank, and the result equals the one-process run.

Volume: every array exactly. Render: each rank builds its piece of the volume,
the ranks gather the arrays the render reads into the whole volume on every
rank, and each renders its rows and columns of the image from it with the same
automatic exposure (taken from a thumbnail of the whole image), so RGB must
match exactly and the float arrays to 1e-5 relative (identical arithmetic; the
tolerance only allows for a different CPU path).
The voronoi case is the volume of Voronoi grains with correlated diameters
(CellId too).
The pvti case reads the volume from a partitioned file, each rank its piece,
and renders it.
Usage: pvpython TestOpalMPI.py N volume|voronoi|render|pvti"""
import os
import sys

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader

import opal_test_config as config
from opal_test_support import check, finish, run

ranks, kind = int(sys.argv[1]), sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
serial = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_serial.vti")
parallel = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_{kind}_parallel.pvti")
mpiexec = [config.MPIEXEC, "-np", str(ranks), config.PVBATCH]

if kind == "pvti":
    # A volume file read by pieces: opal-volume writes it as one .vti and as a
    # .pvti of 4 pieces; each rank reads only its piece of the .pvti (checked
    # against the .vti), the render asks for no more (checked after it), and
    # the render of the pieces equals the one-process render of the .vti.
    reader = os.path.join(here, "opal_render_file.py")
    whole = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_pvti_volume.vti")
    pieces = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_pvti_volume.pvti")
    volume = [config.OPAL_VOLUME, "--dimensions", "48", "24", "60", "--domain-count", "60"]
    run(volume + ["-o", whole])
    written = run(volume + ["-o", pieces, "--pieces", "4"]).stdout
    check("(4 pieces)" in written, "opal-volume says it wrote 4 pieces")
    run([config.PVBATCH, reader, whole, serial, "96", "72"])
    read_by_ranks = run(mpiexec[:-1] + [config.PVBATCH, "--symmetric", reader, pieces, parallel, "96", "72",
                                        "--pieces-of", whole]).stdout
    check(read_by_ranks.count(" read extent ") == 2 * ranks,
          f"each of the {ranks} ranks read its own piece, before the render and after it:\n" + read_by_ranks)
else:
    arguments = ["48", "24", "60"] + (["96", "72"] if kind == "render" else []) + \
        (["--voronoi"] if kind == "voronoi" else [])
    writer = os.path.join(here, "opal_write_pipeline.py")
    run([config.PVBATCH, writer, serial] + arguments)
    run(mpiexec + [writer, parallel] + arguments)


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    return reader


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
