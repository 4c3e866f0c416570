"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_live_view.py):
in the client's own render view the volume is shown as "Opal Spectral" by
default (the cabochon in colour), and turning the camera 10 degrees between
two renders changes the stone's pixels."""
import opal_test_config as config
from opal_test_support import check, finish, run_gui_script

text = run_gui_script("opal_gui_live_view.py", config.PLUGIN, config.PARAVIEW, config.OUTPUT_DIRECTORY)
print(text)
check(text.strip().endswith("passed"), "the GUI's view shows the stone and turning the camera changes it")
finish("TestOpalGuiLiveView")
