"""Runnable pvpython / pvbatch example: a tilt movie of an opal. The stone is
turned about x from -TILT to +TILT degrees under the paper's fixed light and
eye, so its domains flash as their Bragg wavelengths sweep; each frame is a
spectral render (OpalSpectralRender's ModelRotation, animated with ParaView's
animation track) shown in true colours, filling the frame.

    pvpython examples/opal_tilt_movie.py PLUGIN OUT.(ogv|avi|png)
        [--preset NAME] [--frames N] [--size W H] [--tilt DEG]

PLUGIN is build/lib/opal/OpalPlugin/OpalPlugin.so. A name ending in .png
writes a PNG series (OUT.0000.png, OUT.0001.png, ...); .ogv (Theora) and .avi
write a movie where ParaView was built with that writer. Each frame renders
the whole stone: about a second per frame at 640 x 480 on two CPU cores
(lavapipe).
"""
import argparse
import os
import sys

from paraview.simple import (ColorBy, CreateView, GetAnimationScene, GetAnimationTrack, LoadPlugin,
                             OutputPort, SaveAnimation, Show, servermanager)

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("plugin")
parser.add_argument("output", help="OUT.ogv, OUT.avi or OUT.png (a PNG series)")
parser.add_argument("--preset", default="fig12")
parser.add_argument("--frames", type=int, default=31)
parser.add_argument("--size", type=int, nargs=2, default=[640, 480], metavar=("W", "H"))
parser.add_argument("--tilt", type=float, default=15.0, help="largest turn about x, degrees")
args = parser.parse_args()
extension = os.path.splitext(args.output)[1].lower()
if extension not in (".ogv", ".avi", ".png"):
    sys.exit(f"opal_tilt_movie: OUT must end in .ogv, .avi or .png, got {args.output!r}")
if args.frames < 2 or not 1 <= args.size[0] <= 4096 or not 1 <= args.size[1] <= 4096:
    sys.exit("opal_tilt_movie: --frames must be at least 2 and --size 1-4096 pixels each way")
if not 0 < args.tilt <= 90:
    sys.exit(f"opal_tilt_movie: --tilt must lie in (0, 90] degrees, got {args.tilt}")

LoadPlugin(args.plugin, remote=False, ns=globals())
volume = OpalVolume(Preset=args.preset)  # noqa: F821 (defined by the plugin)
render = OpalSpectralRender(Input=OutputPort(volume, 0), ImageSize=args.size)  # noqa: F821

# The image in true colours (the RGB array as it is, Map Scalars off), pixel
# for pixel: a parallel camera on the image plane whose view spans the points
# 0 .. W-1, 0 .. H-1 with each screen pixel's centre on one point.
view = CreateView("RenderView")
view.ViewSize = args.size
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [0, 0, 0]
view.UseFXAA = 0  # anti-aliasing would blur the stone's edge and its domains
display = Show(render, view)
ColorBy(display, ("POINTS", "RGB"))
display.MapScalars = 0
display.InterpolateTextures = 0
view.InteractionMode = "2D"
view.CameraPosition = [(args.size[0] - 1) / 2.0, (args.size[1] - 1) / 2.0, 1000.0]
view.CameraFocalPoint = [(args.size[0] - 1) / 2.0, (args.size[1] - 1) / 2.0, 0.0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = args.size[1] / 2.0

# ModelRotation[0] (about x) from -tilt to +tilt over the frames.
track = GetAnimationTrack("ModelRotation", index=0, proxy=render)
start = servermanager.animation.CompositeKeyFrame()
start.KeyTime, start.KeyValues = 0.0, [-args.tilt]
end = servermanager.animation.CompositeKeyFrame()
end.KeyTime, end.KeyValues = 1.0, [args.tilt]
track.KeyFrames = [start, end]
scene = GetAnimationScene()
scene.PlayMode = "Sequence"
scene.NumberOfFrames = args.frames

if not SaveAnimation(args.output, view, ImageResolution=args.size, FrameWindow=[0, args.frames - 1]):
    sys.exit(f"opal_tilt_movie: the animation could not be written to {args.output}")
print(f"opal_tilt_movie: {args.frames} frames of {args.preset}, {-args.tilt:g} to {args.tilt:g} degrees about x,"
      f" written to {args.output}")
