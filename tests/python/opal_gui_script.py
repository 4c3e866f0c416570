"""Run by the ParaView GUI (paraview --script=...) under xvfb: with the plugin
loaded on start-up, creates an Opal Volume and an Opal Spectral Render, checks
the image, shows it, and ends the application with 0 (1 on any failure)."""
import os
import traceback

try:
    from paraview.simple import OpalSpectralRender, OpalVolume, Render, Show, servermanager

    volume = OpalVolume(Dimensions=[40, 20, 50], DomainCount=20)
    render = OpalSpectralRender(Input=volume, ImageSize=[32, 24])
    render.UpdatePipeline()
    image = servermanager.Fetch(render)
    assert image.GetDimensions() == (32, 24, 1), image.GetDimensions()
    assert image.GetPointData().GetArray("RGB").GetRange(1)[1] > 0, "the image is not black"
    Show(render)
    Render()
    os._exit(0)
except BaseException:
    traceback.print_exc()
    os._exit(1)
