"""Run by the ParaView client (paraview --script) under Xvfb for
TestOpalGuiFinalFrames (docs/design.md §5.2): in the GUI a still render does
not wait for the final frame.

0. The first view: Render() returns at once, before even a preview (the
   device's volume, the pipelines and the light field are made on the
   worker), an interactive render meanwhile draws nothing and waits for
   nothing, and the stone appears without input.
1. After a camera change, Render() returns with the preview drawn (the
   representation's LastFrameQuality 1, no final frame completed yet).
2. The script then returns to the GUI's event loop and only watches, on a
   timer, without rendering: the final frame replaces the preview by itself
   (LastFrameQuality 0), and the window's pixels change from the preview to
   the final image, which equals a screenshot (a screenshot always renders
   its final frame at once) pixel for pixel within 1 level.
3. A new camera while a final frame renders abandons it: two camera changes
   in a row complete one final frame and abandon one.

The verdict goes to OPAL_GUI_VERDICT (the client's stdout is not the test's),
then the client is ended."""
import os
import time

import numpy
from paraview.simple import GetActiveViewOrCreate, LoadPlugin, OutputPort, Render, Show

from opal_gui_verdict import TimedSteps, Verdict, grab, screenshot

verdict = Verdict()
lines, check, end = verdict.lines, verdict.check, verdict.end


class FinalFrames(TimedSteps):
    """The steps, run by the interactor's timer (a Qt timer) in the event loop."""

    def __init__(self, view, stone):
        self.view, self.stone = view, stone
        # About 3 minutes of ticks: far more than a frame takes on lavapipe.
        super().__init__(verdict, 1800)
        self.step = self.wait_for_first_view
        self.started = time.time()

    def info(self, name):
        self.stone.SMProxy.UpdatePropertyInformation()
        return self.stone.SMProxy.GetProperty(name).GetElement(0)

    def look_from(self, eye):
        self.view.CameraPosition, self.view.CameraFocalPoint, self.view.CameraViewUp = eye, [0, 2, 0], [0, 0, -1]
        Render(self.view)

    def wait_for_first_view(self):
        if self.info("LastFrameQuality") != 0:
            return
        lines.append(f"the first view's final frame was drawn {time.time() - self.started:.2f} s after its render")
        self.eye = [0, 40, 0]
        self.started = time.time()
        self.look_from(self.eye)
        lines.append(f"the still render after the camera change returned in {time.time() - self.started:.2f} s")
        check(self.info("LastFrameQuality") == 1, "it returned with the preview drawn")
        # Counted once taken or dropped.
        self.completed_before = self.info("CompletedFinalFrames")
        self.preview = grab(self.view, "gui-final-frame-preview.png")
        self.step = self.wait_for_final

    def wait_for_final(self):
        if self.info("LastFrameQuality") != 0:
            return
        lines.append(f"the final frame was drawn {time.time() - self.started:.2f} s after the still render "
                     f"began, {self.ticks} ticks of the event loop later")
        self.completed = self.info("CompletedFinalFrames")
        check(self.completed == self.completed_before + 1, "by the GUI's own render, once its final frame completed")
        self.final = grab(self.view, "gui-final-frame-drawn.png")
        stone_pixels = self.final.max(axis=2) > 20
        changed = numpy.mean(numpy.abs(self.final - self.preview).max(axis=2)[stone_pixels] > 8)
        check(stone_pixels.mean() > 0.1 and changed > 0.05, f"the window changed from the preview to the final "
              f"frame ({100 * changed:.0f}% of the stone's {100 * stone_pixels.mean():.0f}% of the view)")
        self.abandoned = self.info("AbandonedFinalFrames")
        # Two camera changes in a row: the first one's final frame is abandoned.
        self.look_from([40 * numpy.sin(numpy.radians(20)), 40 * numpy.cos(numpy.radians(20)), 0])
        self.look_from([40 * numpy.sin(numpy.radians(-20)), 40 * numpy.cos(numpy.radians(-20)), 0])
        check(self.info("LastFrameQuality") == 1, "a new camera draws a preview first")
        self.step = self.wait_for_second_final

    def wait_for_second_final(self):
        if self.info("LastFrameQuality") != 0:
            return
        completed, abandoned = self.info("CompletedFinalFrames"), self.info("AbandonedFinalFrames") - self.abandoned
        completed -= self.completed
        check(completed == 1 and abandoned == 1, f"the camera changed while its final frame rendered: that frame "
              f"was abandoned ({abandoned} abandoned), the last camera's completed ({completed} completed)")
        # A screenshot renders its final frame at once: the same image the window showed.
        self.look_from(self.eye)
        shot = screenshot(self.view, "gui-final-frame-screenshot.png")
        check(shot.shape == self.final.shape and numpy.abs(shot - self.final).max() <= 1,
              f"the final frame drawn without input equals a screenshot's within 1 level (sizes {shot.shape}, "
              f"{self.final.shape})")
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
    started = time.time()
    Render(view)  # the first render resets the camera
    steps = FinalFrames(view, stone)
    lines.append(f"the first render returned in {time.time() - started:.2f} s")
    check(steps.info("FinalFramesInBackground") == 1, "the GUI renders final frames in the background")
    check(steps.info("LastFrameQuality") == -1, "the first render returned before drawing the stone")
    started = time.time()
    view.SMProxy.InteractiveRender()  # a drag begun at once
    lines.append(f"an interactive render meanwhile returned in {time.time() - started:.2f} s")
    check(steps.info("LastFrameQuality") == -1, "a drag before the first view arrives draws nothing, waiting for nothing")
    # Into the event loop: from here on only the timer looks, nothing renders but the GUI.
    steps.start(view, 100)
except Exception as error:  # the verdict must be written whatever happens
    check(False, f"error: {error!r}")
    end()
