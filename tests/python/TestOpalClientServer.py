"""pvpython: the live view in client-server runs (docs/design.md §5.2). A
pvserver (1 rank, then 2 ranks under mpiexec) renders "Opal Spectral" for a
pvpython client, and the client's screenshot equals the built-in session's:
each server rank renders the whole stone from the whole volume and ParaView
composites the ranks' frames by depth, which are equal. With ShareMarch the
2 ranks march the frame together, each holding its piece of the volume's
layers, to the same screenshot (that they do is TestOpalMPI view-march's:
a client reads a representation's information from its own copy, which
renders nothing).

Server and clients share one virtual display: the script runs itself again
under xvfb-run (two xvfb-runs started at once can race for a display)."""
import os
import socket
import subprocess
import sys
import time

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import opal_test_config as config
from opal_test_support import check, child_environment, finish, on_virtual_display, run

ON_DISPLAY = "OPAL_CLIENT_SERVER_ON_DISPLAY"
if not os.environ.get(ON_DISPLAY):
    environment = dict(child_environment(), **{ON_DISPLAY: "1"})
    result = subprocess.run(on_virtual_display([config.PVPYTHON, os.path.abspath(__file__)], "640x480x24"),
                            env=environment, capture_output=True, text=True, timeout=280)
    print(result.stdout, result.stderr[-4000:] if result.returncode else "")
    sys.exit(result.returncode)

here = os.path.dirname(os.path.abspath(__file__))
scene = os.path.join(here, "opal_client_server_scene.py")
output = os.path.join(config.OUTPUT_DIRECTORY, "client_server")
os.makedirs(output, exist_ok=True)


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)


def served(ranks, share=False):
    """The screenshot a client takes of a pvserver with `ranks` ranks (the
    ranks marching shared where `share`); a failed client is reported with
    the server's log."""
    port = free_port()
    server = [config.PVSERVER, f"--server-port={port}"]
    if ranks > 1:
        server = [config.MPIEXEC, "-np", str(ranks)] + server
    log_path = os.path.join(output, f"pvserver{ranks}{'-shared' if share else ''}.log")
    with open(log_path, "w") as log:
        process = subprocess.Popen(server, env=child_environment(), stdout=log, stderr=subprocess.STDOUT)
    try:
        for _ in range(600):  # up to 60 s for the server to listen
            if "Accepting connection" in open(log_path).read() or process.poll() is not None:
                break
            time.sleep(0.1)
        path = os.path.join(output, f"served{ranks}{'-shared' if share else ''}.png")
        try:
            run([config.PVPYTHON, scene, config.PLUGIN, path, str(port)] + (["share"] if share else []), timeout=120)
        except RuntimeError as error:
            # The server's log without loguru's "ERR|" marks, which fail the test by themselves.
            log = open(log_path).read()[-1500:].replace("ERR|", "ERR ")
            raise RuntimeError(f"{error}\nserver log ({ranks} rank(s)): {log}") from None
        return pixels(path)
    finally:
        process.terminate()
        process.wait(timeout=30)


builtin_path = os.path.join(output, "builtin.png")
run([config.PVPYTHON, scene, config.PLUGIN, builtin_path], timeout=120)
builtin = pixels(builtin_path)
background = builtin[0]
stone = numpy.mean(numpy.any(numpy.abs(builtin - background) > 12, axis=1))
check(0.1 < stone < 0.9, f"the built-in view shows the stone ({100 * stone:.0f}% of the view)")
for ranks, share in ((1, False), (2, False), (2, True)):
    image = served(ranks, share)
    differing = numpy.mean(numpy.any(numpy.abs(image - builtin) > 2, axis=1))
    how = " marching shared" if share else ""
    # Equal arithmetic on server and client: any pixel off by more than 2 levels is an error.
    check(image.shape == builtin.shape and differing == 0,
          f"pvserver with {ranks} rank(s){how}: the client's view equals the built-in one "
          f"({100 * differing:.2f}% of pixels differ)")
finish("TestOpalClientServer")
