"""Helpers shared by the pvpython tests."""
import os
import random
import shutil
import subprocess
import sys

# Settings of ours that child MPI jobs must keep; everything else OMPI_/PMIX_
# describes pvpython's own MPI singleton and would confuse a child mpiexec.
_KEEP = {"OMPI_ALLOW_RUN_AS_ROOT", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM",
         "OMPI_MCA_rmaps_base_oversubscribe"}


def child_environment():
    """The environment for launching mpiexec or pvbatch from inside pvpython."""
    return {key: value for key, value in os.environ.items()
            if key in _KEEP or not key.startswith(("OMPI_", "PMIX_"))}


# What a client says when the virtual display xvfb-run started cannot be
# reached (seen now and then on a loaded machine, before any of our code runs).
_NO_DISPLAY = "bad X server connection"


def _on_new_display(command):
    """The command on a virtual display of its own: xvfb-run's under another
    number, or a client that shared its parent's display under an xvfb-run of its own."""
    if command[:1] == ["xvfb-run"] and "-n" in command:
        retry = list(command)
        retry[retry.index("-n") + 1] = str(random.randint(100, 30100))
        return retry
    return ["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", "-screen 0 1280x1024x24", *command]


def run(command, timeout=240):
    """Runs a child process with a clean MPI environment; raises on failure with its output.
    A client that cannot reach its display (before any of our code runs) is run
    again on a display of its own, twice at most: several MPI ranks opening
    windows at once meet it more often, and a client sharing its test's display
    met it once in a CI run."""
    result = subprocess.run(command, env=child_environment(), capture_output=True, text=True,
                            timeout=timeout)
    for _ in range(2):
        if result.returncode == 0 or _NO_DISPLAY not in result.stdout + result.stderr or not shutil.which("xvfb-run"):
            break
        result = subprocess.run(_on_new_display(command), env=child_environment(), capture_output=True, text=True,
                                timeout=timeout)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {result.returncode}:\n"
                           f"{result.stdout[-4000:]}\n{result.stderr[-4000:]}")
    return result


def run_gui_script(script, plugin, paraview, output_directory, arguments=()):
    """Runs tests/gui/`script` in the ParaView client (paraview --script) on a
    virtual display of its own, with the client's further `arguments`; returns
    the verdict it wrote (the client's stdout is not the test's), or "no
    verdict written"."""
    here = os.path.dirname(os.path.abspath(__file__))
    output = os.path.join(output_directory, "gui")
    os.makedirs(output, exist_ok=True)
    verdict = os.path.join(output, os.path.splitext(script)[0] + "-verdict.txt")
    if os.path.exists(verdict):
        os.remove(verdict)
    os.environ["OPAL_GUI_VERDICT"] = verdict
    os.environ["OPAL_PLUGIN"] = plugin
    gui = os.path.join(here, "..", "gui")  # the scripts' shared module, opal_gui_verdict
    os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [gui, os.environ.get("PYTHONPATH")]))
    run(["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", "-screen 0 1280x1024x24",
         paraview, "--script=" + os.path.join(gui, script), *arguments], timeout=280)
    return open(verdict).read() if os.path.exists(verdict) else "no verdict written"


# The checks of one test script: each failed one is printed and counted;
# finish() prints the verdict and exits non-zero if any failed.
failures = []


def check(condition, what):
    """Records a failed check, printing what should hold; returns the condition."""
    if not condition:
        failures.append(what)
        print("FAILED:", what)
    return condition


def finish(name, detail=""):
    """Prints `name: passed|FAILED [detail]` and exits with the verdict."""
    print(f"{name}:", "FAILED" if failures else "passed", *([detail] if detail else []))
    sys.exit(1 if failures else 0)
