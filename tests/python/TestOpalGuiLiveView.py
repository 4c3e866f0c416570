"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_live_view.py):
in the client's own render view the volume is shown as "Opal Spectral" by
default (the cabochon in colour), and turning the camera 10 degrees between
two renders changes the stone's pixels."""
import os
import random

import opal_test_config as config
from opal_test_support import check, finish, run

here = os.path.dirname(os.path.abspath(__file__))
script = os.path.join(here, "..", "gui", "opal_gui_live_view.py")
output = os.path.join(config.OUTPUT_DIRECTORY, "gui")
os.makedirs(output, exist_ok=True)
verdict = os.path.join(output, "gui-live-verdict.txt")
if os.path.exists(verdict):
    os.remove(verdict)
os.environ["OPAL_GUI_VERDICT"] = verdict
os.environ["OPAL_PLUGIN"] = config.PLUGIN
run(["xvfb-run", "-a", "-n", str(random.randint(100, 30100)), "-s", "-screen 0 1280x1024x24",
     config.PARAVIEW, f"--script={script}"], timeout=280)
text = open(verdict).read() if os.path.exists(verdict) else "no verdict written"
print(text)
check(text.strip().endswith("passed"), "the GUI's view shows the stone and turning the camera changes it")
finish("TestOpalGuiLiveView")
