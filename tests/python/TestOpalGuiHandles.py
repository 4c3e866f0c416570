"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_handles.py):
the render's Light and Eye handles (docs/design.md §5.3) are labelled and
coloured apart in the 3-D view where they coincide, a drag there moves the
Light, and they are not drawn in the Opal Image View."""
import opal_test_config as config
from opal_test_support import check, finish, run_gui_script

text = run_gui_script("opal_gui_handles.py", config.PLUGIN, config.PARAVIEW, config.OUTPUT_DIRECTORY)
print(text)
check(text.strip().endswith("passed"), "the handles are labelled, apart, the light on top, and only in 3-D views")
finish("TestOpalGuiHandles")
