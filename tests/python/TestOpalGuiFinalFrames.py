"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_final_frames.py):
a still render after a camera change returns with the preview drawn; with
the event loop running and no further input the final frame, rendered in
the background, replaces it (equal to a screenshot's); a new camera while a
final frame renders abandons it (docs/design.md §5.2)."""
import os
import random

import opal_test_config as config
from opal_test_support import check, finish, run

here = os.path.dirname(os.path.abspath(__file__))
script = os.path.join(here, "..", "gui", "opal_gui_final_frames.py")
output = os.path.join(config.OUTPUT_DIRECTORY, "gui")
os.makedirs(output, exist_ok=True)
verdict = os.path.join(output, "gui-final-frames-verdict.txt")
if os.path.exists(verdict):
    os.remove(verdict)
os.environ["OPAL_GUI_VERDICT"] = verdict
os.environ["OPAL_PLUGIN"] = config.PLUGIN
run(["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", "-screen 0 1280x1024x24",
     config.PARAVIEW, f"--script={script}"], timeout=280)
text = open(verdict).read() if os.path.exists(verdict) else "no verdict written"
print(text)
check(text.strip().endswith("passed"), "the GUI draws the preview at once and the final frame without input")
finish("TestOpalGuiFinalFrames")
