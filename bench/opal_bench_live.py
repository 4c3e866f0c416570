"""Bench of the live view (run under pvbatch on a display, e.g. xvfb-run):
the "Opal Spectral" representation of the paper-scale fig12 volume in a
render view. Prints the preview frames per second while the camera orbits
(the window rendering at an interactive update rate, as during a drag) at
320 x 240, with the headlight (the light moves with the eye: light pass every
frame) and with a fixed light (the march only); then the time from the last
camera change to the final frame at 640 x 480 (a still render).
Goals (lavapipe, 2 cores): >= 10 preview frames/s at 320 x 240; final <= 0.6 s.
Usage: opal_bench_live.py PLUGIN"""
import math
import sys
import time

from paraview.simple import CreateView, LoadPlugin, OutputPort, Render, Show

LoadPlugin(sys.argv[1], remote=False, ns=globals())
volume = OpalVolume(Preset="fig12")  # noqa: F821 (from the plugin)
view = CreateView("RenderView")
view.OrientationAxesVisibility = 0
stone = Show(OutputPort(volume, 0), view)
stone.SetRepresentationType("Opal Spectral")


def place(angle_degrees):
    angle = math.radians(angle_degrees)
    view.CameraPosition = [60 * math.sin(angle), 60 * math.cos(angle), 0]
    view.CameraFocalPoint = [0, 2, 0]
    view.CameraViewUp = [0, 0, -1]
    view.CameraViewAngle = 24


def orbit_fps(frames):
    """Interactive renders (as during a drag: ParaView's InteractiveRender), orbiting."""
    start = time.perf_counter()
    for f in range(frames):
        place(-10 + 20.0 * f / frames)
        view.SMProxy.InteractiveRender()
    return frames / (time.perf_counter() - start)


view.ViewSize = [320, 240]
Render(view)  # the first render resets the camera, uploads the volume and compiles the pipelines
place(0)
Render(view)
orbit_fps(2)  # compiles the preview's pipelines
place(0)
Render(view)
print("opal live-view bench: fig12 (160x80x200), Opal Spectral representation, lavapipe")
print(f"  preview orbit 320x240, headlight:   {orbit_fps(12):.1f} frames/s (goal >= 10)")
stone.Headlight = 0
stone.OpalLightPosition = [0, 60, 0]
place(0)
Render(view)  # the fixed light's field
print(f"  preview orbit 320x240, fixed light: {orbit_fps(12):.1f} frames/s")
stone.Headlight = 1
view.ViewSize = [640, 480]
for label, angle in (("warm-up", 5), ("measured", 7)):
    place(angle)
    start = time.perf_counter()
    Render(view)
    seconds = time.perf_counter() - start
print(f"  final frame 640x480 after a camera change (headlight): {seconds:.2f} s (goal <= 0.6 s)")
