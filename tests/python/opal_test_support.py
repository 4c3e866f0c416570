"""Helpers shared by the pvpython tests."""
import os
import random
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


def on_virtual_display(command, screen="1280x1024x24"):
    """The command on a virtual display of its own (Xvfb through xvfb-run).
    xvfb-run -a takes the first free display from -n on, racily: a random
    start keeps two runs on one machine apart. -noreset: Xvfb resets when its
    last client leaves, and a client that connects during the reset is refused
    ("bad X server connection", and ParaView aborts). ParaView's processes open
    a window to probe the display and close it before they open their own, so
    one rank's probe ending could refuse another rank's window: 6 of 20 runs of
    the 3-rank view failed so without -noreset, none of 48 with it."""
    return ["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", f"-screen 0 {screen} -noreset", *command]


def run(command, timeout=240):
    """Runs a child process with a clean MPI environment; raises on failure
    (or past `timeout` seconds) with its output."""
    try:
        result = subprocess.run(command, env=child_environment(), capture_output=True, text=True,
                                timeout=timeout)
    except subprocess.TimeoutExpired as expired:
        raise RuntimeError(f"{' '.join(command)} ran past {timeout} s:\n"
                           f"{_text(expired.stdout)[-4000:]}\n{_text(expired.stderr)[-4000:]}") from None
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {result.returncode}:\n"
                           f"{result.stdout[-4000:]}\n{result.stderr[-4000:]}")
    return result


def _text(output):
    """What a process that ran too long had written (bytes, text or nothing)."""
    if isinstance(output, bytes):
        return output.decode(errors="replace")
    return output or ""


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
    run(on_virtual_display([paraview, "--script=" + os.path.join(gui, script), *arguments]), timeout=280)
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
