"""Run by the ParaView client (paraview --script) under Xvfb for
TestOpalGuiRefinement (docs/design.md §5.2): the live view's frame budget and
its progressive final frames.

0. The first view arrives by itself (it renders on the worker).
1. Frame budget: a drag (interactive renders) under a budget no preview can
   keep takes the coarsest previews (PreviewScale 16), under a budget any
   preview keeps the finest (1), with no budget (0) half the pixels (2).
2. Progressive: after the coarse drag, the still render draws the drag's
   preview, and the script then only watches on a timer: the view is refined
   by itself, pass by pass (a quarter, a half of the pixels each way, then the
   final frame: three background frames), the window changing at each, the
   progress of the pass under way told (RefinementProgress, which the GUI
   shows in its status bar), and the last one equals a screenshot's pixels
   within 1 level.
3. A camera change during the refinement abandons it at once.

The verdict goes to OPAL_GUI_VERDICT, then the client is ended."""
import math
import os
import time

import numpy
from paraview.simple import GetActiveViewOrCreate, LoadPlugin, OutputPort, Render, Show

from opal_gui_verdict import TimedSteps, Verdict, grab, screenshot

verdict = Verdict()
lines, check, end = verdict.lines, verdict.check, verdict.end


def place(view, degrees):
    angle = math.radians(degrees)
    view.CameraPosition = [40 * math.sin(angle), 40 * math.cos(angle), 0]
    view.CameraFocalPoint, view.CameraViewUp = [0, 2, 0], [0, 0, -1]


def info(stone, name):
    stone.SMProxy.UpdatePropertyInformation()
    return stone.SMProxy.GetProperty(name).GetElement(0)


def drag(view, stone, budget):
    """Six interactive renders (ParaView's InteractiveRender, as a drag does); the last preview's scale."""
    stone.FrameBudget = budget
    for frame in range(6):
        place(view, -6 + 2 * frame)
        view.SMProxy.InteractiveRender()
    return info(stone, "LastPreviewScale")


class Refinement(TimedSteps):
    """The steps, run by the interactor's timer in the event loop."""

    def __init__(self, view, stone):
        self.view, self.stone = view, stone
        super().__init__(verdict, 3600)  # 3 minutes: far more than the passes take on lavapipe
        self.step = self.wait_for_first_view
        self.progress = []

    def wait_for_first_view(self):
        """The first view renders on the worker; a drag before it arrives draws nothing."""
        if info(self.stone, "LastFrameQuality") != 0:
            return
        scales = {budget: drag(self.view, self.stone, budget) for budget in (1000.0, 0.0)}
        scales[0.001] = drag(self.view, self.stone, 0.001)
        check(scales == {1000.0: 1, 0.0: 2, 0.001: 16},
              f"the previews' scale follows the budget: {scales} (budget seconds: scale)")
        Render(self.view)  # still: the drag's last preview, then the passes in the background
        check(info(self.stone, "LastFrameQuality") == 1, "the still render returned with the preview drawn")
        self.drawn = [grab(self.view)]
        self.completed = info(self.stone, "CompletedFinalFrames")
        self.step = self.watch
        self.started = time.time()

    def watch(self):
        self.progress.append(info(self.stone, "RefinementProgress"))
        window = grab(self.view)
        if numpy.abs(window - self.drawn[-1]).max() > 0:
            self.drawn.append(window)
            lines.append(f"pass {len(self.drawn) - 1} drawn {time.time() - self.started:.2f} s after the still render")
        if info(self.stone, "LastFrameQuality") != 0:
            return
        passes = info(self.stone, "CompletedFinalFrames") - self.completed
        check(passes == 3, f"the held view was refined in three passes without input ({passes} completed, "
              f"{len(self.drawn) - 1} changes of the window)")
        check(len(self.drawn) >= 3, "the window changed as the passes arrived")
        running = [p for p in self.progress if p >= 0]
        check(running and max(running) < 3 and self.progress[-1] == -1,
              f"the progress of the passes under way was told (from {min(running or [-1]):.2f} to "
              f"{max(running or [-1]):.2f} of 3), and none once the last was drawn")
        shot = screenshot(self.view, "gui-refinement-screenshot.png")
        check(shot.shape == window.shape and numpy.abs(shot - window).max() <= 1,
              "the last pass equals a screenshot's final frame within 1 level")
        # A new camera during the refinement: the passes of the old one stop.
        self.abandoned = info(self.stone, "AbandonedFinalFrames")
        drag(self.view, self.stone, 0.001)
        place(self.view, 9)
        Render(self.view)
        place(self.view, 11)
        Render(self.view)
        self.step = self.wait_for_second
        self.completed = info(self.stone, "CompletedFinalFrames")

    def wait_for_second(self):
        if info(self.stone, "LastFrameQuality") != 0:
            return
        abandoned = info(self.stone, "AbandonedFinalFrames") - self.abandoned
        check(abandoned >= 1, f"a camera change during the refinement abandoned its pass ({abandoned})")
        end()


try:
    LoadPlugin(os.environ["OPAL_PLUGIN"], remote=False, ns=globals())
    volume = OpalVolume(Dimensions=[80, 40, 100], DomainCount=120)  # noqa: F821 (from the plugin)
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    view.UseFXAA = 0
    stone = Show(OutputPort(volume, 0), view)
    Render(view)  # the first render resets the camera
    place(view, 0)
    Render(view)
    steps = Refinement(view, stone)
    steps.start(view, 50)
except Exception as error:  # the verdict must be written whatever happens
    check(False, f"error: {error!r}")
    end()
