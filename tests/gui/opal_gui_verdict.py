"""What the GUI test scripts share (run by paraview --script, whose stdout is
not the test's; tests/python's run_gui_script puts this folder on the path):
the verdict file and the client's end, the checks, and the window's pixels."""
import os

from paraview.simple import SaveScreenshot
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

# Screenshots go beside the verdict.
OUTPUT = os.path.dirname(os.environ["OPAL_GUI_VERDICT"])


def end_with_verdict(lines, passed):
    """Writes the lines and "passed" or "FAILED" to OPAL_GUI_VERDICT and ends
    the client: the GUI would wait for its user."""
    with open(os.environ["OPAL_GUI_VERDICT"], "w") as out:
        out.write("\n".join(lines + ["passed" if passed else "FAILED"]) + "\n")
    os._exit(0)


class Verdict:
    """A script's lines and checks: "passed" only if there were checks and all held."""

    def __init__(self):
        self.lines, self.checks = [], []

    def check(self, condition, what):
        self.checks.append(bool(condition))
        self.lines.append(f"{'ok' if condition else 'FAILED'}: {what}")

    def end(self):
        end_with_verdict(self.lines, bool(self.checks) and all(self.checks))


def pixels_of(image):
    """An RGB(A) vtkImageData's pixels as a height x width x 3 int array (rows bottom up)."""
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int).reshape(height, width, 3)


def grab(view, name=None):
    """The window's pixels as drawn last (no new render), written to OUTPUT/name if named."""
    grabber = vtkWindowToImageFilter()
    grabber.SetInput(view.GetRenderWindow())
    grabber.ShouldRerenderOff()
    grabber.ReadFrontBufferOff()
    grabber.Update()
    if name:
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(OUTPUT, name))
        writer.SetInputConnection(grabber.GetOutputPort())
        writer.Write()
    return pixels_of(grabber.GetOutput())


def screenshot(view, name, size=None):
    """A screenshot (which waits for the final frame) at the view's size or `size`, read back."""
    path = os.path.join(OUTPUT, name)
    SaveScreenshot(path, view, ImageResolution=list(size or view.ViewSize))
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return pixels_of(reader.GetOutput())


class TimedSteps:
    """Steps run by the interactor's timer in the GUI's event loop: each tick
    calls self.step (set by the subclass; a step ends the client through the
    verdict). Past `limit` ticks, or on an error, the verdict says so and the
    client ends: the verdict must be written whatever happens."""

    def __init__(self, verdict, limit):
        self.verdict, self.limit, self.ticks = verdict, limit, 0

    def tick(self, caller, event):
        self.ticks += 1
        try:
            if self.ticks > self.limit:
                self.verdict.check(False, f"the steps end (stuck in {self.step.__name__})")
                self.verdict.end()
            self.step()
        except Exception as error:
            self.verdict.check(False, f"error: {error!r}")
            self.verdict.end()

    def start(self, view, period_ms):
        """Into the event loop: from here on only the timer looks."""
        interactor = view.GetInteractor()
        interactor.AddObserver("TimerEvent", self.tick)
        interactor.CreateRepeatingTimer(period_ms)
