"""What the GUI test scripts share (run by paraview --script, whose stdout is
not the test's; tests/python's run_gui_script puts this folder on the path):
the verdict file and the client's end."""
import os


def end_with_verdict(lines, passed):
    """Writes the lines and "passed" or "FAILED" to OPAL_GUI_VERDICT and ends
    the client: the GUI would wait for its user."""
    with open(os.environ["OPAL_GUI_VERDICT"], "w") as out:
        out.write("\n".join(lines + ["passed" if passed else "FAILED"]) + "\n")
    os._exit(0)
