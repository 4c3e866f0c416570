"""pvpython: the live view in client-server runs (docs/design.md §5.2). A
pvserver (1 rank, then 2 ranks under mpiexec) renders "Opal Spectral" for a
pvpython client, and the client's screenshot equals the built-in session's:
each server rank renders the whole stone from the whole volume and ParaView
composites the ranks' frames by depth, which are equal.

Server and clients share one virtual display: the script runs itself again
under xvfb-run (two xvfb-runs started at once can race for a display)."""
import os
import random
import socket
import subprocess
import sys
import time

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import opal_test_config as config
from opal_test_support import check, child_environment, finish, run

ON_DISPLAY = "OPAL_CLIENT_SERVER_ON_DISPLAY"
if not os.environ.get(ON_DISPLAY):
    environment = dict(child_environment(), **{ON_DISPLAY: "1"})
    result = subprocess.run(["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", "-screen 0 640x480x24",
                             config.PVPYTHON, os.path.abspath(__file__)],
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


# What a server says where its display refused it a window: "bad X server
# connection" (it aborts, and the client loses it), or, where the ranks'
# probe for a window failed, that it cannot render remotely (the client then
# draws what it holds: no stone).
DISPLAY_REFUSED = ("bad X server connection",
                   "require remote rendering which, however, is not available")


def served(ranks):
    """The screenshot a client takes of a pvserver with `ranks` ranks. The
    virtual display sometimes refuses a new window under load
    (DISPLAY_REFUSED): such an attempt is printed with the server's log and
    tried again, twice at most."""
    for attempt in range(3):
        try:
            return served_once(ranks, attempt)
        except RuntimeError as error:
            log = open(os.path.join(output, f"pvserver{ranks}-{attempt}.log")).read()
            # Printed without loguru's "ERR|" marks, which fail the test by themselves.
            report = f"attempt {attempt + 1} with {ranks} rank(s) failed: {str(error)[:300]}\nserver log: {log[-1500:]}"
            print(report.replace("ERR|", "ERR "))
            if not any(sign in log for sign in DISPLAY_REFUSED):
                raise
    raise RuntimeError(f"pvserver with {ranks} rank(s): no attempt got a display")


def served_once(ranks, attempt):
    port = free_port()
    server = [config.PVSERVER, f"--server-port={port}"]
    if ranks > 1:
        server = [config.MPIEXEC, "-np", str(ranks)] + server
    log_path = os.path.join(output, f"pvserver{ranks}-{attempt}.log")
    with open(log_path, "w") as log:
        process = subprocess.Popen(server, env=child_environment(), stdout=log, stderr=subprocess.STDOUT)
    try:
        for _ in range(600):  # up to 60 s for the server to listen
            if "Accepting connection" in open(log_path).read() or process.poll() is not None:
                break
            time.sleep(0.1)
        path = os.path.join(output, f"served{ranks}.png")
        run([config.PVPYTHON, scene, config.PLUGIN, path, str(port)], timeout=120)
        if DISPLAY_REFUSED[1] in open(log_path).read():
            raise RuntimeError("the server could not render remotely (its display refused it a window)")
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
for ranks in (1, 2):
    image = served(ranks)
    differing = numpy.mean(numpy.any(numpy.abs(image - builtin) > 2, axis=1))
    # Equal arithmetic on server and client: any pixel off by more than 2 levels is an error.
    check(image.shape == builtin.shape and differing == 0,
          f"pvserver with {ranks} rank(s): the client's view equals the built-in one "
          f"({100 * differing:.2f}% of pixels differ)")
finish("TestOpalClientServer")
