"""The ParaView GUI under Xvfb (paraview --script tests/gui/opal_gui_refinement.py):
the previews' resolution follows the frame budget, and a held view is refined
pass by pass without input to the final frame, equal to a screenshot's
(docs/design.md §5.2)."""
import opal_test_config as config
from opal_test_support import check, finish, run_gui_script

text = run_gui_script("opal_gui_refinement.py", config.PLUGIN, config.PARAVIEW, config.OUTPUT_DIRECTORY)
print(text)
check(text.strip().endswith("passed"), "the budget sets the previews and the held view refines by itself")
finish("TestOpalGuiRefinement")
