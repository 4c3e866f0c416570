"""python3 + numpy: OpalCore's coupled-wave Bragg reflectance (docs/design.md §7.1)
against an independent transfer-matrix computation of the same index profile.

The profile is the one whose Fourier component at G = 2 pi / d is eps_G:
eps(z) = eps_bar + 2 eps_G sin(2 pi z / d + cut) over N periods, embedded in
n_bar on both sides, cut into thin homogeneous sublayers and solved exactly
with 2x2 characteristic matrices (Born & Wolf §1.6) for s and p polarisation at
the glancing angle theta2 inside; R is averaged over two cuts a quarter period
apart (see cut_average). The two agree in the peak, the stop band's width
(between the first zeros, and at half maximum) and the first side lobe on
either side, for N = 10, 50, 500, at normal incidence and at theta2 = 65 deg
(where the p coupling |cos 2 theta_n| = 0.64 differs from a mistaken cos
theta2 = 0.42; at 60 deg both are 0.5), for silica spheres in water
(rho = eps_G / eps_bar = 1.5%) and in air (5.4%). Halving the sublayers moves
every compared number by under a tenth of its bound (the test checks), and
sampling four times finer by under 1% of it.

Bounds: coupled-wave theory is first order in rho. Its second-order misses
are a shift of the band by ~rho^2 lambda_B, which is ~rho of the band's width
(~rho lambda_B), and corrections of order rho to kappa; both are largest for
the p wave at 65 deg (measured: side lobes moved by 0.35 rho of the width,
widths off by 0.06 rho, a weak peak by 0.07 rho). So the peak and both
widths must agree to 0.5 rho relative, side-lobe positions to rho of the stop
band's width, and side-lobe heights to 0.5 rho plus twice the square of the
lobe's relative detuning (the cut average's residue, 0.6% at N = 10). For
silica/water that is 0.7% in the widths: kappa off by 1% fails.

    python3 TestOpalCoupledWave.py PATH/TO/OpalCoupledWaveProbe
"""
import math
import subprocess
import sys

import numpy

from opal_test_support import check, finish

PROBE = sys.argv[1]
DIAMETER_NM = 250.0
SPACING_NM = DIAMETER_NM * math.sqrt(2.0 / 3.0)  # d111
FILLING = math.pi / math.sqrt(18.0)               # close packing
X111 = math.pi * math.sqrt(1.5)                   # |G111| r
CONTRASTS = {"silica/water": (1.45, 1.33), "silica/air": (1.45, 1.0)}
LAYERS = (10, 50, 500)
GLANCING_DEGREES = (90.0, 65.0)
SUBLAYERS = 128      # per period; the convergence check halves it
SAMPLES = 8001       # wavelengths per curve (see wavelength_grid)


def crystal(sphere, matrix):
    """eps_bar and eps_111 of close-packed spheres, docs/design.md §7.1, written out here."""
    eps_mean = FILLING * sphere ** 2 + (1 - FILLING) * matrix ** 2
    j1 = (math.sin(X111) - X111 * math.cos(X111)) / X111 ** 2
    return eps_mean, FILLING * (sphere ** 2 - matrix ** 2) * 3 * j1 / X111


def wavelength_grid(eps_mean, eps_g, sin_glancing, layers):
    """Wavelengths uniform in the detuning delta, out past the third zero beyond the band edges:
    some 2000 samples or more per stop-band width, so sampling moves no feature by a tenth of a bound."""
    n_mean = math.sqrt(eps_mean)
    bragg = 2 * SPACING_NM * n_mean * sin_glancing
    kappa = math.pi * abs(eps_g) / (n_mean * bragg * sin_glancing)
    thickness = layers * SPACING_NM
    reach = 1.05 * math.sqrt(kappa ** 2 + (3.5 * math.pi / thickness) ** 2)
    delta = numpy.linspace(-reach, reach, SAMPLES)
    return bragg / (1 + delta * SPACING_NM / math.pi)


def probe(wavelengths, eps_mean, eps_g, sin_glancing, layers):
    """R_s and R_p from OpalCore's coupled-wave model (the probe program)."""
    command = [PROBE, "--spacing-nm", repr(SPACING_NM), "--mean-index", repr(math.sqrt(eps_mean)),
               "--fourier-component", repr(eps_g), "--sin-glancing", repr(sin_glancing),
               "--layers", str(layers)]
    text = "\n".join(repr(float(w)) for w in wavelengths)
    result = subprocess.run(command, input=text, capture_output=True, text=True, check=True)
    table = numpy.array([line.split() for line in result.stdout.splitlines()], dtype=float)
    assert numpy.allclose(table[:, 0], wavelengths, rtol=1e-15), "the probe echoes the wavelengths"
    return {"s": table[:, 1], "p": table[:, 2]}


def period_matrix(wavelengths, eps_mean, eps_g, sin_glancing, polarisation, sublayers, cut):
    """The characteristic matrix of one period, sublayer by sublayer (Born & Wolf §1.6)."""
    tangential = eps_mean * (1 - sin_glancing ** 2)   # (n sin theta)^2, conserved
    z = (numpy.arange(sublayers) + 0.5) / sublayers
    # A staircase of midpoint samples has sinc(1 / sublayers) of the sine's Fourier component at G:
    # scaled up, its component is eps_G exactly and the rest lies at harmonics (sublayers +- 1) G.
    amplitude = 2 * eps_g / numpy.sinc(1 / sublayers)
    eps = eps_mean + amplitude * numpy.sin(2 * math.pi * z + cut)
    normal = numpy.sqrt(eps - tangential)             # n cos theta in each sublayer
    admittance = normal if polarisation == "s" else eps / normal
    phase = numpy.outer(2 * math.pi / wavelengths, normal * SPACING_NM / sublayers)
    matrix = numpy.broadcast_to(numpy.eye(2, dtype=complex), (len(wavelengths), 2, 2))
    for j in range(sublayers):
        c, s = numpy.cos(phase[:, j]), numpy.sin(phase[:, j])
        layer = numpy.empty((len(wavelengths), 2, 2), dtype=complex)
        layer[:, 0, 0] = layer[:, 1, 1] = c
        layer[:, 0, 1] = 1j * s / admittance[j]
        layer[:, 1, 0] = 1j * s * admittance[j]
        matrix = matrix @ layer
    return matrix


def transfer_matrix(wavelengths, eps_mean, eps_g, sin_glancing, layers, polarisation, sublayers, cut):
    """R of N periods, cut at phase `cut` of the profile, between half-spaces of eps_bar."""
    m = numpy.linalg.matrix_power(
        period_matrix(wavelengths, eps_mean, eps_g, sin_glancing, polarisation, sublayers, cut), layers)
    normal = math.sqrt(eps_mean) * sin_glancing
    y = normal if polarisation == "s" else eps_mean / normal
    top = y * m[:, 0, 0] + y * y * m[:, 0, 1] - m[:, 1, 0] - y * m[:, 1, 1]
    bottom = y * m[:, 0, 0] + y * y * m[:, 0, 1] + m[:, 1, 0] + y * m[:, 1, 1]
    return numpy.abs(top / bottom) ** 2


def cut_average(wavelengths, eps_mean, eps_g, sin_glancing, layers, polarisation, sublayers):
    """R averaged over the lattice cut at a node (sin) and at a crest (cos, with
    its index step at the faces) of the profile.

    Coupled-wave theory keeps only the synchronous Fourier term e^{iGz}; the
    other, e^{-iGz}, adds an amplitude delta / (G + delta) times the first
    whose sign depends on where the lattice is cut: +-2 delta / G in R, 15% at
    N = 10's side lobes. It cancels in the average of two cuts a quarter period
    apart, leaving (delta / G)^2: the model is of a lattice cut anywhere."""
    return 0.5 * sum(transfer_matrix(wavelengths, eps_mean, eps_g, sin_glancing, layers, polarisation,
                                     sublayers, cut) for cut in (0.0, 0.5 * math.pi))


def extremum(x, r, i):
    """The vertex of the parabola through samples i-1, i, i+1: (position, value)."""
    a, b, c = numpy.polyfit(x[i - 1:i + 2] - x[i], r[i - 1:i + 2], 2)
    if a == 0:
        return x[i], r[i]
    return x[i] - b / (2 * a), c - b * b / (4 * a)


def walk(r, i, step, downhill):
    """From sample i, step while R keeps falling (downhill) or rising; 1e-12 absorbs a flat top's rounding."""
    sign = 1 if downhill else -1
    while 0 < i + step < len(r) - 1 and sign * (r[i + step] - r[i]) < 1e-12:
        i += step
    return i


def half_maximum(x, r, top, zero, level):
    """Where R falls through `level` from the peak to the first zero, linearly interpolated; at the
    zero when a strong band's narrow notch there falls between samples, hiding the crossing."""
    step = 1 if zero > top else -1
    i = top
    while i + step != zero and r[i + step] > level:
        i += step
    j = i + step
    if r[j] > level:
        return x[j]
    return x[i] + (level - r[i]) * (x[j] - x[i]) / (r[j] - r[i])


def features(x, r):
    """Peak, widths between first zeros and at half maximum, first side lobes (both sides), in nm."""
    top = int(numpy.argmax(r))
    peak = r[top]
    zeros = [walk(r, top, step, True) for step in (-1, 1)]
    lobes = [extremum(x, r, walk(r, zero, step, False)) for zero, step in zip(zeros, (-1, 1))]
    halves = [half_maximum(x, r, top, zero, peak / 2) for zero in zeros]
    return {
        "peak": peak,
        "zero width": abs(extremum(x, r, zeros[1])[0] - extremum(x, r, zeros[0])[0]),
        "half width": abs(halves[1] - halves[0]),
        "lobes": lobes,
    }


def compare(coupled, exact):
    """Relative differences: peak, widths, side-lobe heights; lobe positions in stop-band widths."""
    width = exact["zero width"]
    pairs = list(zip(coupled["lobes"], exact["lobes"]))
    return {
        "peak": abs(coupled["peak"] / exact["peak"] - 1),
        "zero width": abs(coupled["zero width"] / width - 1),
        "half width": abs(coupled["half width"] / exact["half width"] - 1),
        "lobe position": max(abs(c[0] - e[0]) / width for c, e in pairs),
        "lobe height": max(abs(c[1] / e[1] - 1) for c, e in pairs),
    }


def bounds(contrast, bragg, exact):
    """What first-order coupled-wave theory owes the exact result (see the module's note)."""
    # The lobes' detuning delta / G = (lambda_B / lambda - 1) / 2 sets the cut average's residue.
    lobe_detuning = max(abs(bragg / position - 1) / 2 for position, _ in exact["lobes"])
    return {
        "peak": 0.5 * contrast,
        "zero width": 0.5 * contrast,
        "half width": 0.5 * contrast,
        "lobe position": contrast,
        "lobe height": 0.5 * contrast + 2 * lobe_detuning ** 2,
    }


def run_case(name, sphere, matrix, layers, glancing, polarisation):
    """Checks one curve: the probe against the transfer matrix, and the latter's convergence."""
    eps_mean, eps_g = crystal(sphere, matrix)
    sin_glancing = math.sin(math.radians(glancing))
    x = wavelength_grid(eps_mean, eps_g, sin_glancing, layers)
    coupled = features(x, probe(x, eps_mean, eps_g, sin_glancing, layers)[polarisation])
    coarse, fine = (features(x, cut_average(x, eps_mean, eps_g, sin_glancing, layers, polarisation, m))
                    for m in (SUBLAYERS // 2, SUBLAYERS))
    error, converged = compare(coupled, fine), compare(coarse, fine)
    bound = bounds(eps_g / eps_mean, 2 * SPACING_NM * math.sqrt(eps_mean) * sin_glancing, fine)
    label = f"{name} N={layers} theta2={glancing:g} {polarisation}"
    print(f"{label}: peak {coupled['peak']:.5f} (transfer matrix {fine['peak']:.5f}); relative errors "
          + ", ".join(f"{key} {value:.1e} (bound {bound[key]:.1e})" for key, value in error.items()))
    for key, value in error.items():
        check(value < bound[key], f"{label}: coupled-wave {key} off by {value:.3g} (bound {bound[key]:.3g})")
        check(converged[key] < 0.1 * bound[key],
              f"{label}: transfer matrix unconverged in {key} ({converged[key]:.3g} on doubling sublayers)")


for name, (sphere, matrix) in CONTRASTS.items():
    for layers in LAYERS:
        for glancing in GLANCING_DEGREES:
            for polarisation in ("s",) if glancing == 90 else ("s", "p"):
                run_case(name, sphere, matrix, layers, glancing, polarisation)
finish("TestOpalCoupledWave")
