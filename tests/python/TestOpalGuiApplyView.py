"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_apply_view.py
while the client plays tests/gui/TestOpalGuiRender.xml, the Properties panel's
Apply of Opal Volume and Opal Spectral Render): after ParaView's own Apply the
3-D view looks down on the stone from +y, view up -z, at the stone's centre;
the Domains are not shown; the stone's first frame arrives by itself."""
import os

import opal_test_config as config
from opal_test_support import check, finish, run_gui_script

recording = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "gui", "TestOpalGuiRender.xml")
text = run_gui_script("opal_gui_apply_view.py", config.PLUGIN, config.PARAVIEW, config.OUTPUT_DIRECTORY,
                      ["--dr", "--test-script=" + recording])
print(text)
check(text.strip().endswith("passed"), "after the GUI's Apply the 3-D view looks down on the stone")
finish("TestOpalGuiApplyView")
