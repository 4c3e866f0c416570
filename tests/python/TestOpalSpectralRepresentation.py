"""pvpython: the "Opal Spectral" representation renders the stone from the
view's camera, equal to Opal Spectral Render for that camera, and composites
with depth (the checks are opal_representation_scene.py's, run under pvbatch
on a virtual display)."""
import os

import opal_test_config as config
from opal_test_support import check, finish, on_virtual_display, run

here = os.path.dirname(os.path.abspath(__file__))
output = os.path.join(config.OUTPUT_DIRECTORY, "representation")
os.makedirs(output, exist_ok=True)
result = run(on_virtual_display([config.PVBATCH, os.path.join(here, "opal_representation_scene.py"),
                                 config.PLUGIN, output]))
print(result.stdout[-3000:])
check("opal_representation_scene: passed" in result.stdout, "every check of the scene passed")
finish("TestOpalSpectralRepresentation")
