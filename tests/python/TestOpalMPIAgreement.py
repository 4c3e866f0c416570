"""pvpython: under MPI the ranks of one render agree (docs/design.md §8.1).
Ranks whose settings differ, a rank without a Vulkan device and a rank whose
settings are refused each give one clear error on every rank, no image piece
on any rank, and no hang (each run is bounded; a hang fails the test);
ranks that agree render. With every order of scattering the ranks share the
photon solve; a rank without a device, or one aborting inside the shared
solve (which aborts every rank's request), leaves every rank without an image
piece, and none hangs. The ranks share the light field: its sweep with the
light above, its march from every voxel with the light low to the side; an
abort inside either ends every rank's request alike, as one inside the
ranks' shared assignment of a Voronoi volume's cells does, and one inside
the view march the ranks share (ShareMarch). A rank that never comes to the
render leaves the others waiting only as long as OPAL_EXCHANGE_WAIT_LIMIT
says: they name the exchange and end the job.
Usage: pvpython TestOpalMPIAgreement.py N"""
import os
import re
import subprocess
import sys

from opal_test_support import check, child_environment, finish
import opal_test_config as config

ranks = int(sys.argv[1])
scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "opal_rank_agreement_scene.py")


def run_ranks_status(case, rank1_environment=None):
    """Runs the scene on `ranks` ranks (rank 1 with its own environment where
    given); returns the job's exit status (None past 180 s) and stdout + stderr."""
    command = [config.MPIEXEC, "-np", "1", config.PVBATCH, "--symmetric", scene, case]
    others = ["-np", str(ranks - 1)] + (["env"] + rank1_environment if rank1_environment else []) + \
        [config.PVBATCH, "--symmetric", scene, case]
    try:
        result = subprocess.run(command + [":"] + others, env=child_environment(), capture_output=True,
                                text=True, timeout=180)
    except subprocess.TimeoutExpired:
        check(False, f"{case}: the ranks finish (no hang)")
        return None, ""
    return result.returncode, result.stdout + result.stderr


def run_ranks(case, rank1_environment=None):
    """Runs the scene on `ranks` ranks; returns stdout + stderr."""
    return run_ranks_status(case, rank1_environment)[1]


def images_of(output):
    """Each rank's image points, as the ranks printed them (their lines may interleave)."""
    return {int(rank): int(points) for rank, points in re.findall(r"rank (\d+) image (\d+)", output)}


def expect_refused(case, sentence, rank1_environment=None):
    output = run_ranks(case, rank1_environment)
    images = images_of(output)
    check(len(images) == ranks, f"{case}: every rank reports:\n{output[-3000:]}")
    check(all(points == 0 for points in images.values()), f"{case}: no rank holds an image piece: {images}")
    said = output.count(sentence)
    check(said == ranks, f"{case}: every rank says '{sentence}' once, said {said} times:\n{output[-3000:]}")


def counts(output, which):
    """Each rank's count of the ranks that shared `which` (shares: the
    every-order solve; light: the light field; cells: the Voronoi cells;
    march: the view march), as the ranks printed them (their lines may interleave)."""
    column = {"shares": 1, "light": 2, "cells": 3, "march": 4}[which]
    lines = re.findall(r"rank (\d+) image \d+ shares (\d+) light (\d+) cells (\d+) march (\d+)", output)
    return {int(line[0]): int(line[column]) for line in lines}


def expect_shared(case, what, which):
    """The ranks agree and render their pieces, all sharing `which`."""
    output = run_ranks(case)
    check(len(images_of(output)) == ranks and all(points > 0 for points in images_of(output).values()),
          f"{what}: ranks that agree render their pieces:\n{output[-3000:]}")
    check(counts(output, which) == {r: ranks for r in range(ranks)},
          f"{what}: all {ranks} ranks shared the {which}: {counts(output, which)}")


def expect_abort(case, step, which, doing):
    """Rank 1 aborts inside the ranks' shared `step`: every rank ends, none
    with an image piece, none `doing` alone. Returns the output."""
    output = run_ranks(case)
    images = images_of(output)
    check(len(images) == ranks and all(points == 0 for points in images.values()),
          f"an abort in the shared {step} on rank 1: every rank ends, none with an image piece: {images}\n{output[-3000:]}")
    check(counts(output, which) == {r: 0 for r in range(ranks)},
          f"{case}: every rank aborts with it, none {doing} alone: {counts(output, which)}")
    return output


def expect_bounded_wait():
    """Rank 1 never comes to the render (as where it stopped, or its pipeline
    failed before it and it went on elsewhere): the others wait in the ranks' agreement before the render no longer
    than the limit (OPAL_EXCHANGE_WAIT_LIMIT, 5 s here), say so naming the
    exchange, and end the job, none with an image."""
    status, output = run_ranks_status("absent")
    if status is None:
        return  # the hang is the failure, said
    check(status != 0, f"absent: the job ends with a failure, ended {status}:\n{output[-3000:]}")
    sentence = "waited 5 s in the ranks' agreement before the render for the other ranks"
    check(sentence in output and "OPAL_EXCHANGE_WAIT_LIMIT" in output,
          f"absent: a waiting rank says '{sentence}', naming the limit:\n{output[-3000:]}")
    check(not images_of(output), f"absent: no rank holds an image: {images_of(output)}")


expect_bounded_wait()
expect_shared("same", "the light above", "light")
expect_refused("settings", f"Rank 1 of {ranks} renders with StepSize 0.5, rank 0 with 0")
expect_refused("information", "ViewAngle")
expect_refused("same", "No Vulkan device", ["OPAL_VULKAN_DEVICE=no-such-device"])
expect_shared("every-order", "every order", "shares")
expect_refused("every-order", "No Vulkan device", ["OPAL_VULKAN_DEVICE=no-such-device"])
output = expect_abort("abort", "solve", "shares", "solving")
check(counts(output, "light") == {r: ranks for r in range(ranks)},
      f"the abort came after the ranks' shared light field: {counts(output, 'light')}")
expect_abort("above-abort", "sweep from above", "light", "computing the light field")
expect_shared("side", "the light to the side", "light")
expect_abort("side-abort", "light march", "light", "computing the light field")
expect_shared("voronoi", "Voronoi grains", "cells")
expect_abort("voronoi-abort", "Voronoi cells", "cells", "assigning the cells")
expect_shared("march", "the view march shared", "march")
expect_abort("march-abort", "view march", "march", "marching")
finish("TestOpalMPIAgreement", f"({ranks} ranks)")
