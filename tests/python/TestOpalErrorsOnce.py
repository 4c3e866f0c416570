"""pvpython: a bad input is reported once and its work done once (issue
#32). A table of volumes with a broken array (missing, two components, one
that fails only after a full render) and a bad setting, shown with the "Opal
Spectral" representation and through Opal Spectral Render: the error naming
the cause appears once over a Show, repeated Renders and an update with
nothing changed, and fixed, it renders with no error (the checks are
opal_errors_once_scene.py's, run under pvbatch on a virtual display)."""
import os

import opal_test_config as config
from opal_test_support import check, finish, on_virtual_display, run

here = os.path.dirname(os.path.abspath(__file__))
output = os.path.join(config.OUTPUT_DIRECTORY, "errors-once")
os.makedirs(output, exist_ok=True)
good = os.path.join(output, "good.vti")
run([config.OPAL_VOLUME, "--dimensions", "30", "20", "30", "--domain-count", "10", "-o", good])
result = run(on_virtual_display([config.PVBATCH, os.path.join(here, "opal_errors_once_scene.py"),
                                 config.PLUGIN, output, good]))
print(result.stdout[-3000:])
check("opal_errors_once_scene: passed" in result.stdout, "every check of the scene passed")
finish("TestOpalErrorsOnce")
