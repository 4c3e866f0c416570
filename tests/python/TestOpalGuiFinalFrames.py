"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_final_frames.py):
a still render after a camera change returns with the preview drawn; with
the event loop running and no further input the final frame, rendered in
the background, replaces it (equal to a screenshot's); a new camera while a
final frame renders abandons it (docs/design.md §5.2)."""
import opal_test_config as config
from opal_test_support import check, finish, run_gui_script

text = run_gui_script("opal_gui_final_frames.py", config.PLUGIN, config.PARAVIEW, config.OUTPUT_DIRECTORY)
print(text)
check(text.strip().endswith("passed"), "the GUI draws the preview at once and the final frame without input")
finish("TestOpalGuiFinalFrames")
