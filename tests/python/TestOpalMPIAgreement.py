"""pvpython: under MPI the ranks of one render agree (docs/design.md §8.1).
Ranks whose settings differ, a rank without a Vulkan device and a rank whose
settings are refused each give one clear error on every rank, no image piece
on any rank, and no hang (each run is bounded; a hang fails the test);
ranks that agree render. With every order of scattering the ranks share the
photon solve; a rank without a device, or one aborting inside the shared
solve (which aborts every rank's request), leaves every rank without an image
piece, and none hangs. The ranks share the light field: its sweep with the
light above, its march from every voxel with the light low to the side; an
abort inside either ends every rank's request alike.
Usage: pvpython TestOpalMPIAgreement.py N"""
import os
import re
import subprocess
import sys

from opal_test_support import check, child_environment, finish
import opal_test_config as config

ranks = int(sys.argv[1])
scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "opal_rank_agreement_scene.py")


def run_ranks(case, rank1_environment=None):
    """Runs the scene on `ranks` ranks (rank 1 with its own environment where
    given); returns stdout + stderr."""
    command = [config.MPIEXEC, "-np", "1", config.PVBATCH, "--symmetric", scene, case]
    others = ["-np", str(ranks - 1)] + (["env"] + rank1_environment if rank1_environment else []) + \
        [config.PVBATCH, "--symmetric", scene, case]
    try:
        result = subprocess.run(command + [":"] + others, env=child_environment(), capture_output=True,
                                text=True, timeout=180)
    except subprocess.TimeoutExpired:
        check(False, f"{case}: the ranks finish (no hang)")
        return ""
    return result.stdout + result.stderr


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



def light_shares(output):
    return {int(rank): int(count) for rank, count in re.findall(r"rank (\d+) image \d+ shares \d+ light (\d+)", output)}


output = run_ranks("same")
images = images_of(output)
check(len(images) == ranks and all(points > 0 for points in images.values()),
      f"ranks that agree render their pieces: {images}\n{output[-3000:]}")
check(light_shares(output) == {r: ranks for r in range(ranks)},
      f"the light above: all {ranks} ranks swept the light field together: {light_shares(output)}")
expect_refused("settings", f"Rank 1 of {ranks} renders with StepSize 0.5, rank 0 with 0")
expect_refused("information", "ViewAngle")
expect_refused("same", "No Vulkan device", ["OPAL_VULKAN_DEVICE=no-such-device"])

output = run_ranks("every-order")
shares = {int(rank): int(count) for rank, count in re.findall(r"rank (\d+) image \d+ shares (\d+)", output)}
check(len(images_of(output)) == ranks and all(points > 0 for points in images_of(output).values()),
      f"every order: ranks that agree render their pieces:\n{output[-3000:]}")
check(shares == {r: ranks for r in range(ranks)}, f"every order: all {ranks} ranks traced the field together: {shares}")
expect_refused("every-order", "No Vulkan device", ["OPAL_VULKAN_DEVICE=no-such-device"])
output = run_ranks("abort")
images = images_of(output)
shares = {int(rank): int(count) for rank, count in re.findall(r"rank (\d+) image \d+ shares (\d+)", output)}
check(len(images) == ranks and all(points == 0 for points in images.values()),
      f"an abort in the shared solve on rank 1: every rank ends, none with an image piece: {images}\n{output[-3000:]}")
check(shares == {r: 0 for r in range(ranks)}, f"and every rank aborts with it, none solving alone: {shares}")
check(light_shares(output) == {r: ranks for r in range(ranks)},
      f"the abort came after the ranks' shared light field: {light_shares(output)}")


def expect_light_abort(case, step):
    """Rank 1 aborts inside the ranks' shared light `step`: every rank ends,
    none with an image piece, none computing the light field alone."""
    output = run_ranks(case)
    images = images_of(output)
    check(len(images) == ranks and all(points == 0 for points in images.values()),
          f"an abort in the shared {step} on rank 1: every rank ends, none with an image piece: {images}\n{output[-3000:]}")
    check(light_shares(output) == {r: 0 for r in range(ranks)},
          f"{case}: every rank aborts with it, none computing the light field alone: {light_shares(output)}")


expect_light_abort("above-abort", "sweep from above")
output = run_ranks("side")
check(len(images_of(output)) == ranks and all(points > 0 for points in images_of(output).values()),
      f"the light to the side: ranks that agree render their pieces:\n{output[-3000:]}")
check(light_shares(output) == {r: ranks for r in range(ranks)},
      f"the light to the side: all {ranks} ranks marched the light field together: {light_shares(output)}")
expect_light_abort("side-abort", "light march")
finish("TestOpalMPIAgreement", f"({ranks} ranks)")
