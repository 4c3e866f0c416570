// The coupled-wave Bragg reflectance (docs/design.md §7.1, §7.2): the GLSL
// port of OpalCore's OpalCoupledWave.cxx (coupledModeReflectance as written
// there, one bounded form for both sides of the band edge), the FCC plane
// families of OpalLatticePlanes.cxx and the reflected lobe.

// Below this y, tanh y / y and sin y / y are 1 - y^2/3 and 1 - y^2/6.
const float CW_SERIES_BELOW = 1e-3;
// tanh(20) is 1 in float; a larger argument may give inf/inf.
const float CW_TANH_SATURATES = 20.0;
// Rays closer than this to the planes (sin theta2) reflect nothing.
const float CW_GRAZING_SIN = 1e-6;

// A = sin(sL)/s outside the band, y = sL (s^2 = delta^2 - kappa^2 > 0).
float sideLobeAmplitude(float s, float y, float thickness)
{
  return y < CW_SERIES_BELOW ? thickness * (1.0 - y * y / 6.0) : sin(y) / s;
}

// R of a grating of coupling kappa, detuning delta (1/nm) and thickness L (nm):
// kappa^2 A^2 / (1 + b^2 A^2) with A = tanh(sL)/s, b = delta inside the band
// (s^2 = kappa^2 - delta^2 >= 0) and A = sin(sL)/s, b = kappa outside.
float coupledModeReflectance(float kappa, float delta, float thickness)
{
  float q2 = kappa * kappa - delta * delta;
  float s = sqrt(abs(q2));
  float y = s * thickness;
  float a;
  if (q2 >= 0.0)
  {
    a = y < CW_SERIES_BELOW ? thickness * (1.0 - y * y / 3.0) : tanh(min(y, CW_TANH_SATURATES)) / s;
  }
  else
  {
    a = sideLobeAmplitude(s, y, thickness);
  }
  float b = q2 >= 0.0 ? delta : kappa;
  float ka2 = kappa * kappa * a * a;
  return ka2 / (1.0 + b * b * a * a);
}

// 3 j1(x) / x, the sphere's form factor (1 at x = 0).
float sphereFormFactor(float x)
{
  if (abs(x) < 1e-2)
  {
    return 1.0 - x * x / 10.0;
  }
  return 3.0 * (sin(x) - x * cos(x)) / (x * x * x);
}

// One plane family and order at one crossing, for a ray of glancing sine
// sin theta2: what R(lambda) needs, computed once per family.
struct CoupledWaveFamily
{
  float braggWavelength; // lambda_B = 2 (d/k) n_bar sin theta2
  float couplingLength;  // kappa_s lambda = pi |eps_kG| / (n_bar sin theta2); 0: reflects nothing
  float polarisationP;   // kappa_p / kappa_s = |cos 2 theta_n| = |2 sin^2 theta2 - 1|
  float detuningScale;   // pi k / d: delta = this x (lambda_B / lambda - 1)
  float thickness;       // L = N d, nm
};

// lambda_B = 2 (d/k) n_bar sin theta2 of period d/k (nm) at glancing sine sin theta2.
float braggWavelengthAt(float period, float sinGlancing)
{
  return 2.0 * period * P.meanIndex * sinGlancing;
}

// Family of period d/k (nm), |eps_kG| and thickness L (nm) seen at glancing sine sin theta2.
CoupledWaveFamily coupledWaveFamily(float sinGlancing, float period, float fourier, float thickness)
{
  // Rays within 1e-6 of grazing, and crossings of no thickness, reflect nothing.
  bool reflects = sinGlancing > CW_GRAZING_SIN && thickness > 0.0;
  return CoupledWaveFamily(braggWavelengthAt(period, sinGlancing),
    reflects ? OPAL_PI * fourier / (P.meanIndex * sinGlancing) : 0.0,
    abs(2.0 * sinGlancing * sinGlancing - 1.0), OPAL_PI / period, thickness);
}

float coupledWaveDetuning(CoupledWaveFamily f, float lambda)
{
  return f.detuningScale * (f.braggWavelength / lambda - 1.0);
}

// R(lambda), s and p averaged (OpalCoupledWave.cxx coupledWaveReflectance).
float coupledWaveReflectance(CoupledWaveFamily f, float lambda)
{
  float delta = coupledWaveDetuning(f, lambda);
  float kappaS = f.couplingLength / lambda;
  return 0.5 * (coupledModeReflectance(kappaS, delta, f.thickness) +
    coupledModeReflectance(kappaS * f.polarisationP, delta, f.thickness));
}

// R averaged over the side lobes' phase: for fixed s = sqrt(delta^2 - kappa^2),
// the mean over sL of kappa^2 sin^2 / (s^2 + kappa^2 sin^2) is 1 - s / |delta|.
float sideLobeAverage(float kappa, float delta)
{
  return 1.0 - sqrt(max(1.0 - (kappa * kappa) / (delta * delta), 0.0));
}

// Whether a bin spans `periods` side-lobe periods (pi / L each in delta) or
// more: a wing bin spanning 4 takes their phase average, else its centre
// value; a band bin spanning 1.5 the closed form (coupledWaveBandAverage).
// Without divisions: delta(c - w/2) - delta(c + w/2) = (pi k/d) lambda_B w / (c^2 - w^2/4).
const float CW_PHASE_AVERAGE_PERIODS = 4.0;
const float CW_CLOSED_BAND_PERIODS = 1.5;
bool spansSideLobes(CoupledWaveFamily f, float centre, float width, float periods)
{
  return f.detuningScale * f.braggWavelength * width * f.thickness >=
    periods * OPAL_PI * (centre * centre - 0.25 * width * width);
}

float sideLobePhaseAverage(CoupledWaveFamily f, float centre)
{
  float delta = coupledWaveDetuning(f, centre), kappaS = f.couplingLength / centre;
  return 0.5 * (sideLobeAverage(kappaS, delta) + sideLobeAverage(kappaS * f.polarisationP, delta));
}

// The integral from 0 to x (odd in x) over x = lambda - lambda_B of a band of
// half-width c (per polarisation) with the side lobes' phase average beside
// it: 1 within |x| <= c, 1 - sqrt(1 - c^2/x^2) beyond (OpalCoupledWave.cxx
// bandIntegral, which derives it).
vec2 bandIntegral(float x, vec2 c)
{
  float ax = max(abs(x), 1e-30);
  vec2 outside = c * c / (ax + sqrt(max(vec2(ax * ax) - c * c, vec2(0.0)))) + c * acos(min(c / ax, vec2(1.0)));
  return sign(x) * mix(vec2(ax), outside, greaterThan(vec2(ax), c));
}

// y / tanh y, 1 at y = 0.
float overTanh(float y)
{
  return y < CW_SERIES_BELOW ? 1.0 + y * y / 3.0 : y / tanh(min(y, CW_TANH_SATURATES));
}

// R averaged over a bin in closed form, s and p (OpalCoupledWave.cxx
// coupledWaveBandAverage): per polarisation a band of peak tanh^2(kappa L)
// and half-width c / tanh(kappa L), the side lobes' phase average beside it,
// which keeps coupled-mode theory's integral of R, pi kappa tanh(kappa L).
float coupledWaveBandAverage(CoupledWaveFamily f, float centre, float width)
{
  vec2 kappaL = f.couplingLength / f.braggWavelength * f.thickness * vec2(1.0, f.polarisationP);
  vec2 depth = tanh(min(kappaL, vec2(CW_TANH_SATURATES)));
  vec2 halfWidth = f.braggWavelength / (f.detuningScale * f.thickness) * vec2(overTanh(kappaL.x), overTanh(kappaL.y));
  float x = centre - 0.5 * width - f.braggWavelength;
  return 0.5 * dot(depth * depth, bandIntegral(x + width, halfWidth) - bandIntegral(x, halfWidth)) / width;
}

// R averaged over a wavelength bin (docs/design.md §7.2). Where the bin comes
// within CW_BAND_KAPPAS couplings of the band: in closed form where the bin
// spans 1.5 side-lobe periods, else at CW_BIN_SAMPLES points (the stop band,
// about 1.5% of lambda for silica in water, is narrower than a 10 nm bin, so
// one sample could miss it; 4 points of its flat top's sharp edges may miss
// the bin's mean by 0.19). In the wings: the side lobes' phase average or the
// centre value (spansSideLobes).
const int CW_BIN_SAMPLES = 4;
const float CW_BAND_KAPPAS = 4.0;
float coupledWaveBinAverage(CoupledWaveFamily f, float centre, float width)
{
  float reach = CW_BAND_KAPPAS * f.couplingLength / f.braggWavelength;
  float shortEdge = coupledWaveDetuning(f, centre - 0.5 * width), longEdge = coupledWaveDetuning(f, centre + 0.5 * width);
  if (longEdge > reach || shortEdge < -reach)
  {
    return spansSideLobes(f, centre, width, CW_PHASE_AVERAGE_PERIODS) ? sideLobePhaseAverage(f, centre)
                                                                      : coupledWaveReflectance(f, centre);
  }
  if (spansSideLobes(f, centre, width, CW_CLOSED_BAND_PERIODS)) return coupledWaveBandAverage(f, centre, width);
  float sum = 0.0;
  for (int i = 0; i < CW_BIN_SAMPLES; ++i)
  {
    sum += coupledWaveReflectance(f, centre + width * ((float(i) + 0.5) / float(CW_BIN_SAMPLES) - 0.5));
  }
  return sum / float(CW_BIN_SAMPLES);
}

// coupledWaveBinAverage of a bin beyond the band's reach whose centre lies
// above lambda_B / 4 (so |delta| > kappa there for both polarisations): the
// same value without the band's forms (coupledWaveBand says which bins), and
// with what both of its forms need computed once, since SIMD lanes evaluate
// both: 1/centre, and per polarisation s = sqrt(delta^2 - kappa^2), from which
// the side lobes' phase average is 1 - s/|delta| and the centre value
// kappa^2 A^2 / (1 + kappa^2 A^2), A = sin(sL)/s (coupledModeReflectance's
// form outside the band, without its tanh form).
float coupledWaveWingAverage(CoupledWaveFamily f, float centre, float width)
{
  float inverseCentre = 1.0 / centre;
  float delta = f.detuningScale * (f.braggWavelength * inverseCentre - 1.0);
  vec2 kappa = f.couplingLength * inverseCentre * vec2(1.0, f.polarisationP);
  vec2 s = sqrt(max(vec2(delta * delta) - kappa * kappa, vec2(0.0)));
  if (spansSideLobes(f, centre, width, CW_PHASE_AVERAGE_PERIODS)) return 1.0 - 0.5 * (s.x + s.y) / abs(delta);
  vec2 y = s * f.thickness;
  vec2 a = vec2(sideLobeAmplitude(s.x, y.x, f.thickness), sideLobeAmplitude(s.y, y.y, f.thickness));
  vec2 ka2 = kappa * kappa * a * a;
  vec2 r = ka2 / (1.0 + ka2);
  return 0.5 * (r.x + r.y);
}

// The wavelengths [lo, hi] that a bin must overlap to need
// coupledWaveBinAverage's band forms: where |delta| = pi k/d |lambda_B/lambda - 1|
// <= CW_BAND_KAPPAS kappa(lambda_B); from 0 if a bin's centre may lie below
// lambda_B / 4 (there kappa(lambda) may exceed |delta| beyond that reach).
vec2 coupledWaveBand(CoupledWaveFamily f, float shortest)
{
  float reach = CW_BAND_KAPPAS * f.couplingLength / (f.braggWavelength * f.detuningScale); // relative to pi k/d
  float lo = 0.26 * f.braggWavelength > shortest ? 0.0 : f.braggWavelength / (1.0 + reach);
  return vec2(lo, reach < 0.5 ? f.braggWavelength / (1.0 - reach) : 1e6);
}

// Bins further than this many couplings kappa_s from lambda_B are skipped:
// there R <= (kappa/delta)^2 < 1/1200, so reflected + transmitted stays
// within 0.1% of what the full R gives.
const float CW_WINDOW_KAPPAS = 35.0;

// The wavelengths [lo, hi] within the window of family f: |delta| <= 35 kappa_s
// where kappa_s ~ 1/lambda: |lambda_B - lambda| <= 35 kappa_s lambda / detuningScale.
vec2 coupledWaveWindow(CoupledWaveFamily f)
{
  float reach = CW_WINDOW_KAPPAS * f.couplingLength / f.detuningScale;
  return vec2(f.braggWavelength - reach, f.braggWavelength + reach);
}

// The FCC families in the crystal frame, in OpalLatticePlanes.cxx's order:
// (111) first (the domain's drawn normal), the rest of {111}, {200}, {220}.
const int FCC_FAMILIES = 13;
const vec3 FCC_MILLER[FCC_FAMILIES] = vec3[](vec3(1, 1, 1), vec3(-1, 1, 1), vec3(1, -1, 1), vec3(1, 1, -1),
  vec3(2, 0, 0), vec3(0, 2, 0), vec3(0, 0, 2), vec3(2, 2, 0), vec3(2, -2, 0), vec3(2, 0, 2), vec3(2, 0, -2),
  vec3(0, 2, 2), vec3(0, 2, -2));

// v turned by the unit quaternion q = (x, y, z, w).
vec3 rotateByQuaternion(vec4 q, vec3 v)
{
  return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v);
}

// The von Mises-Fisher lobe of angular deviation `spread` (radians) about the
// unit direction `centre`, at the unit direction `at`: normalised on the
// sphere (its integral over all directions is 1), peak ~ 1/(2 pi spread^2);
// 0 beyond 4.3 spread, where exp(-(4.3)^2 / 2) = 1e-4 of the peak (the tail
// holds 1e-4 of the reflected light), so a family whose lobe misses the eye
// costs no bin loop. cos - 1 is written as -|at - centre|^2 / 2, exact near the peak.
const float CW_LOBE_CUT = 1e-4;
float reflectedLobe(vec3 centre, vec3 at, float spread)
{
  float concentration = 1.0 / (spread * spread);
  vec3 d = at - centre;
  float shape = exp(-0.5 * concentration * dot(d, d));
  return shape < CW_LOBE_CUT ? 0.0 : concentration / (2.0 * OPAL_PI * (1.0 - exp(-2.0 * concentration))) * shape;
}
