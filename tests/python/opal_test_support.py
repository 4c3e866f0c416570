"""Helpers shared by the pvpython tests."""
import os
import subprocess

# Settings of ours that child MPI jobs must keep; everything else OMPI_/PMIX_
# describes pvpython's own MPI singleton and would confuse a child mpiexec.
_KEEP = {"OMPI_ALLOW_RUN_AS_ROOT", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM",
         "OMPI_MCA_rmaps_base_oversubscribe"}


def child_environment():
    """The environment for launching mpiexec or pvbatch from inside pvpython."""
    return {key: value for key, value in os.environ.items()
            if key in _KEEP or not key.startswith(("OMPI_", "PMIX_"))}


def run(command, timeout=240):
    """Runs a child process with a clean MPI environment; raises on failure with its output."""
    result = subprocess.run(command, env=child_environment(), capture_output=True, text=True,
                            timeout=timeout)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited {result.returncode}:\n"
                           f"{result.stdout[-4000:]}\n{result.stderr[-4000:]}")
    return result
