// Every render parameter once (docs/design.md §1.1). A row is
//   X(Name, Type, Count, Min, Max, Choices, Flag, FromVolume, Description)
// Name        the member of opal::RenderParameters (whose initialiser is the
//             default), vtkOpalSpectralRender's Set/Get and ParaView's property
// Type        int, double or bool as VTK and ParaView hold it (enumerations: int)
// Count       components (1-4)
// Min, Max    each component's allowed range, inclusive (validate refuses
//             beyond; -OPAL_UNBOUNDED, OPAL_UNBOUNDED: none, only finite)
// Choices     an enumeration's names for 0, 1, ..., space-separated; "" otherwise
// Flag        opal-render's flag; "" where it sets the parameter otherwise
// FromVolume  1: VTK's and ParaView's default is 0, which takes the volume's
//             value (the preset's image size, the model's index); 0: the default
// Description one line (CLI help, the Python docs, docs/design.md)
// The VTK class, PrintSelf, the CLI, validate's ranges, the fuzzer and the
// tests against the ParaView XML loop over this list. Plain preprocessor
// text: VTK's wrappers expand it too.
#pragma once

#define OPAL_UNBOUNDED 1.79769313486231570815e+308

#define OPAL_RENDER_PARAMETERS(X)                                                                          \
  X(ImageSize, int, 2, 0, 16384, "", "--image-size", 1,                                                    \
    "Image width and height in pixels (0 0: the volume's preset's, 640 x 480 for custom)")                 \
  X(ImageRegion, int, 4, -16384, 16384, "", "--image-region", 0,                                           \
    "Renders only x0 y0 width height of the image, from the top left (<= 0 reaches the edge)")             \
  X(EyePosition, double, 3, -1e6, 1e6, "", "--eye-position", 0, "Eye position in mm")                      \
  X(FocalPoint, double, 3, -1e6, 1e6, "", "--focal-point", 0, "Point the eye looks at, in mm")             \
  X(ViewUp, double, 3, -1e6, 1e6, "", "--view-up", 0, "Image up direction (the opal's long axis vertical)") \
  X(ViewAngle, double, 1, 0, 179, "", "--view-angle", 0, "Vertical view angle in degrees, in (0, 179)")    \
  X(LightPosition, double, 3, -1e6, 1e6, "", "--light-position", 0,                                        \
    "D65 point light position in mm (at the eye: paper section 7)")                                        \
  X(LightRadius, double, 1, 1e-6, 1000, "", "--light-radius", 0, "Radius of the light's sphere in mm")     \
  X(ModelRotation, double, 3, -OPAL_UNBOUNDED, OPAL_UNBOUNDED, "", "--model-rotation", 0,                                        \
    "Turns the stone by degrees about x, then y, then z, after the preset's placement (fig13: 5 about x)")  \
  X(WavelengthRange, double, 2, 200, 1000, "", "--wavelength-range", 0, "Wavelengths min max in nm")       \
  X(WavelengthStep, double, 1, 0.01, 800, "", "--wavelength-step", 0, "Wavelength step in nm")             \
  X(RefractiveIndex, double, 1, 0, 4, "", "", 1,                                                           \
    "Refractive index mu of opal, in [1, 4) (0: the volume's; the CLI takes the model's)")                 \
  X(BraggBandwidth, double, 1, 0, 1, "", "--bragg-bandwidth", 0,                                           \
    "Relative full width of the Bragg band B, in (0, 1)")                                                  \
  X(DiffractionGain, double, 1, 0, 1000, "", "--diffraction-gain", 0,                                      \
    "Gain G of diffraction (the paper's doubled amplitude: 4, eq. 9)")                                     \
  X(BraggOrders, int, 1, 1, 8, "", "--bragg-orders", 0, "Bragg orders k = 1..BraggOrders (the paper: 1)")   \
  X(MosaicSpread, double, 1, 0, 90, "", "--mosaic-spread", 0,                                              \
    "Angular gating of diffraction towards the mirror direction in degrees (0: off, the paper)")           \
  X(BraggModel, int, 1, 0, 1, "paper coupled-wave", "--bragg-model", 0,                                    \
    "paper (the box band of gain G) or coupled-wave (the lattice layers' reflectance into a lobe)")        \
  X(LatticePlanes, int, 1, 0, 1, "111 fcc", "--lattice-planes", 0,                                         \
    "111 (the stacking planes) or fcc (all 13 families; needs coupled-wave)")                              \
  X(CoherentLayers, int, 1, 1, MaxCoherentLayers, "", "--coherent-layers", 0,                                         \
    "The most lattice layers that reflect coherently")                                                     \
  X(EnergyConservation, bool, 1, 0, 1, "", "--energy-conservation", 0,                                     \
    "Light behind a domain keeps 1 - R of it on the view path (always with coupled-wave)")                 \
  X(ScatteringOrders, int, 1, 0, 2, "volume single all", "--scattering-orders", 1,                         \
    "single (the paper's) or all (every bounce in the body; default: single for the paper's figures, else all)") \
  X(ScatteringPhotons, int, 1, 1000, 100000000, "", "--scattering-photons", 0,                             \
    "Photons per spectral node of the every-order solve (fewer: faster, noisier)")                         \
  X(Exposure, double, 1, 0, MaxExposure, "", "--exposure", 0,                                              \
    "Exposure multiplier, at most 1e30 (0: automatic, the body's median luminance to 0.18)")               \
  X(Background, double, 3, 0, 1, "", "--background", 0, "Background colour, sRGB in [0, 1]")               \
  X(StepSize, double, 1, 0, OPAL_UNBOUNDED, "", "--step-size", 0, "Longest march sub-step in mm (0: one voxel)") \
  X(SpecularSamples, int, 1, 1, 16, "", "--specular-samples", 0, "Sub-rays per pixel axis for the highlight") \
  X(PixelSamples, int, 1, 1, 16, "", "--pixel-samples", 0,                                                  \
    "Sub-rays per pixel axis where the stone's outline or a domain's edge crosses a pixel (1: one ray)")    \
  X(SpectralNodes, int, 1, 0, 64, "", "--spectral-nodes", 0,                                               \
    "Nodes of the body's scattering spectrum, 4-64 (0: evaluate every wavelength)")                        \
  X(LightFalloffAtEntry, bool, 1, 0, 1, "", "--light-falloff-at-entry", 0,                                 \
    "The paper's eq. 6: the 1/r^2 fall-off stops at the light's entry point")                              \
  X(WriteSpectrum, bool, 1, 0, 1, "", "", 0,                                                               \
    "Adds the Spectrum array, one value per wavelength per pixel (the CLI: by its outputs)")               \
  X(Quality, int, 1, 0, 1, "final preview", "--quality", 0,                                                \
    "final, or preview: 1/PreviewScale of the width and height, 20 nm steps, 8 spectral nodes, a 2 x 2 highlight, 1 ray per pixel") \
  X(PreviewScale, int, 1, 1, 64, "", "--preview-scale", 0,                                                 \
    "A preview's pixels: 1/PreviewScale of the width and of the height (the live view's frame budget sets it)") \
  X(Illuminant, int, 1, 0, 1, "D65 none", "--illuminant", 0,                                               \
    "The light's spectrum: D65 (luminance 1), or none (unit spectral irradiance)")
