"""Run by the ParaView client (paraview --script) under Xvfb for
TestOpalGuiApplyView, while the client plays tests/gui/TestOpalGuiRender.xml
(--test-script: a user's Sources > Opal Volume, Apply, Filters > Opal
Spectral Render, Apply, through the Properties panel's Apply button, so
ParaView's own pqApplyBehavior shows the outputs): once both are applied,
the 3-D view looks down on the stone from +y with view up -z, as the
render's default camera does (docs/design.md §5.2; vtkSMOpalVolumeSourceProxy),
its focal point the stone's box's centre; the Domains output is not shown;
and the stone's first frame arrives by itself (LastFrameQuality 0) with the
stone in the window.

This script only loads the plugin (so the menus hold the Opal proxies when
the playback starts) and watches on a timer of the event loop; it renders
nothing itself. The verdict goes to OPAL_GUI_VERDICT, then the client is ended."""
import os
import time

import numpy
from paraview.simple import GetActiveView, GetSources, GetViews, LoadPlugin

from opal_gui_verdict import TimedSteps, Verdict, grab

verdict = Verdict()
lines, check, end = verdict.lines, verdict.check, verdict.end


def source_named(xml_name):
    found = [proxy for proxy in GetSources().values() if proxy.GetXMLName() == xml_name]
    return found[0] if found else None


def representation_in(view, proxy, port):
    """The view's representation of the proxy's output port, or None."""
    for representation in view.Representations:
        inputs = representation.SMProxy.GetProperty("Input") if representation.SMProxy else None
        if inputs and inputs.GetNumberOfProxies() and inputs.GetProxy(0) == proxy.SMProxy and \
                inputs.GetOutputPortForConnection(0) == port:
            return representation
    return None


class Watch(TimedSteps):
    def __init__(self, view):
        self.view = view
        # About 4 minutes of ticks: far more than the playback and a first frame take on lavapipe.
        super().__init__(verdict, 2400)
        self.step = self.wait_for_apply
        self.started = time.time()

    def wait_for_apply(self):
        """Until the playback has applied the render: its image is shown in an Opal Image View."""
        self.volume, render = source_named("OpalVolume"), source_named("OpalSpectralRender")
        if not self.volume or not render:
            return
        image_views = [view for view in GetViews() if view.GetXMLName() == "OpalImageView" and
                       representation_in(view, render, 0) and representation_in(view, render, 0).Visibility]
        if not image_views:
            return
        lines.append(f"both applied {time.time() - self.started:.1f} s after the script ended")
        self.stone = representation_in(self.view, self.volume, 0)
        check(self.stone is not None and self.stone.Visibility == 1 and
              self.stone.Representation == "Opal Spectral", "the 3-D view shows the stone as Opal Spectral")
        domains = representation_in(self.view, self.volume, 1)
        check(domains is None or domains.Visibility == 0, "the Domains output is not shown")
        camera = self.view.GetActiveCamera()
        position, focal, up = (numpy.array(value) for value in
                               (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp()))
        direction = (position - focal) / numpy.linalg.norm(position - focal)
        bounds = numpy.array(self.volume.GetDataInformation().GetBounds()).reshape(3, 2)
        centre = bounds.mean(axis=1)
        lines.append(f"camera: position {position.round(3).tolist()}, focal point {focal.round(3).tolist()}, "
                     f"view up {up.round(3).tolist()}; the stone's box {bounds.round(3).tolist()}")
        check(numpy.abs(direction - [0, 1, 0]).max() < 1e-6, "the eye is straight above the stone (+y)")
        check(numpy.abs(up - [0, 0, -1]).max() < 1e-6, "the view up is -z (the stone's long axis upright)")
        check(numpy.abs(focal - centre).max() < 1e-6 * max(1.0, numpy.abs(centre).max()),
              "the camera looks at the stone's box's centre")
        self.started = time.time()
        self.step = self.wait_for_first_view

    def wait_for_first_view(self):
        self.stone.SMProxy.UpdatePropertyInformation()
        if self.stone.SMProxy.GetProperty("LastFrameQuality").GetElement(0) != 0:
            return
        lines.append(f"the first view's final frame was drawn {time.time() - self.started:.1f} s after both applied")
        window = grab(self.view, "gui-apply-view.png")
        background = window[2, window.shape[1] // 2]  # the top edge's middle: the view's background
        stone = numpy.abs(window - background).max(axis=2) > 12
        share = stone.mean()
        lines.append(f"the stone covers {100 * share:.0f}% of the 3-D view ({window.shape[1]} x {window.shape[0]})")
        check(0.1 < share < 0.95, "the stone is drawn in the 3-D view")
        end()


try:
    LoadPlugin(os.environ["OPAL_PLUGIN"], remote=False, ns=globals())
    view = GetActiveView()
    watch = Watch(view)
    watch.start(view, 100)
except Exception as error:  # the verdict must be written whatever happens
    check(False, f"error: {error!r}")
    end()
