"""pvpython: the Bragg map in the coupled-wave model (docs/design.md §7.3)
against closed forms computed here with numpy, independently of OpalCore:
for sampled domain voxels and an oblique light, every FCC plane family's
lambda_B = 2 d n sin theta2 (d = sqrt(2) D / |hkl|, n the mean index of
spheres and matrix, theta2 between the light and the family's planes, their
normals turned by the voxel's LatticeOrientation quaternion) and its peak
reflectance (tanh^2(kappa N d), s and p averaged, kappa from the sphere form
factor); the (111) family is BraggWavelength and BraggPeakReflectance; the
paper's model adds no reflectance array."""
import numpy
from paraview import servermanager as sm
from paraview.simple import LoadPlugin
from vtkmodules.util.numpy_support import vtk_to_numpy

import opal_test_config as config
from opal_test_support import check, finish

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
SPHERE, MATRIX, LAYERS = 1.45, 1.0, 50
FILLING = numpy.pi / numpy.sqrt(18.0)
MILLER = numpy.array([(1, 1, 1), (-1, 1, 1), (1, -1, 1), (1, 1, -1), (2, 0, 0), (0, 2, 0), (0, 0, 2),
                      (2, 2, 0), (2, -2, 0), (2, 0, 2), (2, 0, -2), (0, 2, 2), (0, 2, -2)], dtype=float)
light = numpy.array([10.0, 50.0, 5.0])

volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=30, SphereRefractiveIndex=SPHERE,  # noqa: F821
                    MatrixRefractiveIndex=MATRIX)
volume.DomainCount = 30  # after the preset's fill
bragg = OpalBraggMap(Input=volume, LightPosition=list(light), BraggModel="coupled-wave",  # noqa: F821
                     LatticePlanes="fcc", CoherentLayers=LAYERS)
bragg.UpdatePipeline()
data = sm.Fetch(bragg)
pd = data.GetPointData()
ids = vtk_to_numpy(pd.GetArray("DomainId"))
voxels = numpy.nonzero(ids >= 0)[0][::7]
check(len(voxels) > 20, f"domain voxels sampled ({len(voxels)})")
points = numpy.array([data.GetPoint(int(i)) for i in voxels])
diameters = vtk_to_numpy(pd.GetArray("ParticleDiameter"))[voxels].astype(float)
quaternions = vtk_to_numpy(pd.GetArray("LatticeOrientation"))[voxels].astype(float)  # w, x, y, z


def rotate(q, v):
    """v turned by the unit quaternion q = (w, x, y, z)."""
    w, u = q[0], q[1:]
    return v + 2.0 * numpy.cross(u, numpy.cross(u, v) + w * v)


mean_index = numpy.sqrt(FILLING * SPHERE ** 2 + (1 - FILLING) * MATRIX ** 2)
toward = (light - points) / numpy.linalg.norm(light - points, axis=1)[:, None]
expected_wavelength = numpy.zeros((len(voxels), 13))
expected_peak = numpy.zeros((len(voxels), 13))
for f, hkl in enumerate(MILLER):
    normals = numpy.array([rotate(q, hkl / numpy.linalg.norm(hkl)) for q in quaternions])
    sin_glancing = numpy.abs(numpy.sum(toward * normals, axis=1))
    spacing = numpy.sqrt(2.0) * diameters / numpy.linalg.norm(hkl)
    wavelength = 2.0 * spacing * mean_index * sin_glancing
    x = numpy.pi * diameters / spacing
    fourier = 3 * FILLING * (SPHERE ** 2 - MATRIX ** 2) * (numpy.sin(x) - x * numpy.cos(x)) / x ** 3  # 3 f de j1(x)/x
    kappa_s = numpy.pi * numpy.abs(fourier) / (mean_index * wavelength * sin_glancing)
    kappa_p = kappa_s * numpy.abs(2 * sin_glancing ** 2 - 1)
    thickness = LAYERS * spacing
    expected_wavelength[:, f] = wavelength
    expected_peak[:, f] = 0.5 * (numpy.tanh(kappa_s * thickness) ** 2 + numpy.tanh(kappa_p * thickness) ** 2)

got_wavelength = vtk_to_numpy(pd.GetArray("FamilyBraggWavelength"))[voxels]
got_peak = vtk_to_numpy(pd.GetArray("FamilyPeakReflectance"))[voxels]
check(numpy.allclose(got_wavelength, expected_wavelength, rtol=1e-4),
      "every family's lambda_B is 2 d n sin theta2: worst relative error "
      f"{numpy.max(numpy.abs(got_wavelength - expected_wavelength) / expected_wavelength):.2e}")
check(numpy.allclose(got_peak, expected_peak, rtol=1e-3, atol=1e-6),
      f"every family's peak reflectance is tanh^2(kappa N d): worst error {numpy.max(numpy.abs(got_peak - expected_peak)):.2e}")
check(numpy.allclose(vtk_to_numpy(pd.GetArray("BraggWavelength"))[voxels], expected_wavelength[:, 0], rtol=1e-4) and
      numpy.allclose(vtk_to_numpy(pd.GetArray("BraggPeakReflectance"))[voxels], expected_peak[:, 0], rtol=1e-3),
      "BraggWavelength and BraggPeakReflectance are the (111) family's")
bragg.BraggModel, bragg.LatticePlanes = "paper", "111"
bragg.UpdatePipeline()
paper = sm.Fetch(bragg).GetPointData()
check(paper.GetArray("BraggPeakReflectance") is None and paper.GetArray("FamilyBraggWavelength") is None,
      "the paper's model adds no reflectance arrays")
finish("TestOpalBraggMapCoupledWave")
