"""pvpython: `mpiexec -np N pvbatch` builds the opal volume as N pieces, one per
rank, and every array equals the one-process volume exactly.
Usage: pvpython TestOpalVolumeMPI.py N"""
import os
import sys

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader

import opal_test_config as config
from opal_test_support import run

ranks = int(sys.argv[1])
dimensions = ["48", "24", "60"]
here = os.path.dirname(os.path.abspath(__file__))
writer = os.path.join(here, "opal_write_volume.py")
os.makedirs(config.OUTPUT_DIRECTORY, exist_ok=True)
serial = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_serial.vti")
parallel = os.path.join(config.OUTPUT_DIRECTORY, f"mpi{ranks}_parallel.pvti")

run([config.PVBATCH, writer, serial] + dimensions)
run([config.MPIEXEC, "-np", str(ranks), config.PVBATCH, writer, parallel] + dimensions)


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    return reader


serial_data = read(vtkXMLImageDataReader, serial).GetOutput()
parallel_reader = read(vtkXMLPImageDataReader, parallel)
parallel_data = parallel_reader.GetOutput()

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)


check(parallel_reader.GetNumberOfPieces() == ranks,
      f"{ranks} pieces written, got {parallel_reader.GetNumberOfPieces()}")
check(serial_data.GetDimensions() == parallel_data.GetDimensions(), "same grid")
names = ["VoxelType", "ParticleDiameter", "Normal", "DomainId", "BraggLambdaMax",
         "BraggLambdaMin", "ScatteringCoefficient", "SurfaceDistance"]
for name in names:
    a = serial_data.GetPointData().GetArray(name)
    b = parallel_data.GetPointData().GetArray(name)
    check(a is not None and b is not None, f"{name} present in both")
    if a is not None and b is not None:
        check(numpy.array_equal(vtk_to_numpy(a), vtk_to_numpy(b)),
              f"{name}: {ranks}-rank volume equals the one-process volume")
print("TestOpalVolumeMPI:", "FAILED" if failures else "passed", f"({ranks} ranks)")
sys.exit(1 if failures else 0)
