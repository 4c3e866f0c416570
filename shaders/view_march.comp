#version 450
// ViewMarchPass (paper §6, docs/design.md §3.4): per pixel, the primary ray meets the
// smooth surface (the zero of SurfaceDistance) and records where its mirror
// ray passes the light (for HighlightPass); the refracted ray (Snell 1 -> mu, carrying 1 - F)
// crosses the opal voxel by voxel (3-D DDA, so no one-voxel-thick domain is
// tunnelled through) and gathers Rayleigh single scattering (eq. 8) and Bragg
// diffraction (eq. 4, 9), each domain once per crossing. With ABSORPTION the
// light and view paths are dimmed by the absorption too (docs/design.md §3.9).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "opal_render_bindings.glsl"

layout(local_size_x = MarchGroupSide, local_size_y = MarchGroupSide) in;
layout(constant_id = MarchWavelengthsConstant) const int WAVELENGTHS = 41;
// The body's scattering spectrum (docs/design.md §3.4): accumulated on
// SPECTRAL_NODES (>= 4) nodes uniform in s = (550/lambda)^4 and resampled once
// per pixel, or with EXACT_SCATTERING evaluated at every wavelength.
layout(constant_id = MarchSpectralNodesConstant) const int SPECTRAL_NODES = 16;
layout(constant_id = MarchExactScatteringConstant) const bool EXACT_SCATTERING = false;
// The volume absorbs: read the absorption cells and their light field.
layout(constant_id = MarchAbsorptionConstant) const bool ABSORPTION = false;
// The coupled-wave Bragg model instead of the paper's box band (docs/design.md §7.2).
layout(constant_id = MarchCoupledWaveConstant) const bool COUPLED_WAVE = false;
// Crossings keep 1 - R of the light behind them on the view path, and of the
// light passing them on the light path (the light pass's Bragg shadows, §7.2);
// always with COUPLED_WAVE.
layout(constant_id = MarchEnergyConservationConstant) const bool ENERGY_CONSERVATION = false;
// The bins' centres, FIRST_WAVELENGTH + l WAVELENGTH_STEP (nm, §3.6), known
// when the pipeline is built: the rounds' resampling unrolls over the bins,
// and each bin's nodes and weights become constants (docs/design.md §3.4).
layout(constant_id = MarchFirstWavelengthConstant) const float FIRST_WAVELENGTH = 380.0;
layout(constant_id = MarchWavelengthStepConstant) const float WAVELENGTH_STEP = 10.0;
// The preview reads the light field of the voxel a point lies in (one load)
// instead of trilinearly (four): a view ray averages it over ~70 voxels.
layout(constant_id = MarchNearestLightConstant) const bool NEAREST_LIGHT = false;
// ScatteringOrders all: the light scattered more than once, a field solved per
// light on the host, adds to the body's scattering (docs/design.md §3.10): read
// from the field per voxel, or evaluated from its tally grid where the field
// does not fit the device's memory (MarchScatteredLight*).
layout(constant_id = MarchScatteredLightConstant) const int SCATTERED_LIGHT_MODE = 0;
const bool SCATTERED_LIGHT = SCATTERED_LIGHT_MODE != MarchScatteredLightNone;
// Rays forwarded between pieces of the volume (docs/design.md §8.1): the
// march walks only the layers z in marchWork.piece and keeps a ray that
// leaves them for the dispatch of the piece it enters.
layout(constant_id = MarchForwardedConstant) const bool FORWARDED = false;
// A forwarded ray's entry trace reads SurfaceDistance only at points in its
// piece, and goes on in the piece of the next (defined below).
bool surfacePointHeld(vec3 p);
#define SURFACE_POINT_HELD(p) surfacePointHeld(p)

#define PAIRED_FIELDS_CONSTANT MarchPairedFieldsConstant
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"
#include "opal_camera.glsl"
#include "opal_coupled_wave.glsl"
#include "opal_voxel_walk.glsl"
#include "opal_bragg_transmission.glsl"
#include "opal_kept_state.glsl"

// The light and absorption fields' LightFieldPairs read as one vec4 each
// (voxel in xy, its +x neighbour in zw): a CPU driver gathers a struct's
// members one by one, a vec4 at once (lavapipe: paper march ~14% faster,
// with absorption ~19%; images bit-identical). Without PAIRED_FIELDS, a vec2
// per voxel.
#ifdef OPAL_VOLUME_ADDRESSES
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer LightFieldRef { LightFieldPairAsVec4 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer LightFieldSingleRef { vec2 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer AbsorptionCellRef { vec2 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer LightShadowRef { LightShadow value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer ScatteredLightRef { vec4 value; };
#define LIGHT_FIELD_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightField, (i), 16u)).value
#define LIGHT_ABSORPTION_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 16u)).value
#define LIGHT_FIELD_SINGLE_AT(i) LightFieldSingleRef(voxelAddress(volumeAddresses.lightField, (i), 8u)).value
#define LIGHT_ABSORPTION_SINGLE_AT(i) LightFieldSingleRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 8u)).value
// Unpaired, the two vec2s from voxel i on: its value and the next voxel's, one load.
#define LIGHT_FIELD_FROM_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightField, (i), 8u)).value
#define LIGHT_ABSORPTION_FROM_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 8u)).value
#define ABSORPTION_CELL_AT(i) AbsorptionCellRef(voxelAddress(volumeAddresses.absorptionCells, (i), 8u)).value
#define LIGHT_SHADOW_AT(i) LightShadowRef(voxelAddress(volumeAddresses.lightShadow, (i), 12u)).value
#define SCATTERED_LIGHT_AT(i) ScatteredLightRef(voxelAddress(volumeAddresses.scatteredLight, (i), 16u)).value
#else
layout(std430, set = 0, binding = LightFieldBinding) readonly buffer LightField { LightFieldPairAsVec4 lightField[]; };
layout(std430, set = 0, binding = AbsorptionCellBinding) readonly buffer AbsorptionCells { vec2 absorptionCells[]; };
layout(std430, set = 0, binding = LightAbsorptionBinding) readonly buffer LightAbsorption { LightFieldPairAsVec4 lightAbsorption[]; };
layout(std430, set = 0, binding = LightShadowBinding) readonly buffer LightShadows { LightShadow lightShadow[]; };
layout(std430, set = 0, binding = ScatteredLightBinding) readonly buffer ScatteredLight { vec4 scatteredLight[]; };
// The fields a piece may hold are read at heldIndex.
#define LIGHT_FIELD_AT(i) lightField[heldIndex(i)]
#define LIGHT_ABSORPTION_AT(i) lightAbsorption[heldIndex(i)]
// Bound fields are always paired (opal_volume_fields.glsl): these read the pair.
#define LIGHT_FIELD_SINGLE_AT(i) lightField[heldIndex(i)].xy
#define LIGHT_ABSORPTION_SINGLE_AT(i) lightAbsorption[heldIndex(i)].xy
#define LIGHT_FIELD_FROM_AT(i) lightField[heldIndex(i)]
#define LIGHT_ABSORPTION_FROM_AT(i) lightAbsorption[heldIndex(i)]
#define ABSORPTION_CELL_AT(i) absorptionCells[mediumIndex(i)]
#define LIGHT_SHADOW_AT(i) lightShadow[heldIndex(i)]
#define SCATTERED_LIGHT_AT(i) scatteredLight[heldIndex(i)]
#endif
#include "opal_scattered_light_grid.glsl"
layout(std430, set = 0, binding = DomainTableBinding) readonly buffer DomainTable { DomainRecord domains[]; };
layout(std430, set = 0, binding = ShadowTableBinding) readonly buffer ShadowTable { vec4 shadowTable[]; };
const int SHADOW_ROW_VEC4S = SHADOW_TABLE_ROW_VEC4S(WAVELENGTHS);
// Per pixel of the rendered rectangle: X, Y, Z, depth (mm, 0 where every ray misses).
// Read by the edge select.
layout(std430, set = 0, binding = PixelColourBinding) buffer PixelColourImage { PixelColour pixelColour[]; };
// Per pixel: dominant Bragg wavelength (nm, 0 if none), its luminance Y, the
// share of its rays that meet the opal, the first domain its centre ray crosses.
layout(std430, set = 0, binding = PixelBraggBinding) buffer PixelBraggImage { PixelBragg pixelBragg[]; };
// Per pixel, WAVELENGTHS spectral radiances (only if P.writeSpectrum != 0);
// the refine adds its sub-rays' into them.
layout(std430, set = 0, binding = PixelSpectrumBinding) buffer PixelSpectrum { float pixelSpectrum[]; };
// Per pixel: where its mirror ray passes the light, for the highlight pass.
layout(std430, set = 0, binding = PixelMirrorBinding) writeonly buffer PixelMirrorImage { PixelMirror pixelMirror[]; };
// The pixels an edge crosses, queued by MarchSelectEdges for MarchRefineEdges.
// [0]: the pixels the select queued, the first `rectangle's pixels` entries
// of edgePixels; [1]: those the refine's first stage leaves open, by their
// place in [0], the entries after.
layout(std430, set = 0, binding = EdgeQueueBinding) buffer EdgeQueue { DispatchQueue edgeQueue[2]; }; // counts
layout(std430, set = 0, binding = EdgePixelsBinding) buffer EdgePixels { uint edgePixels[]; };
// A queued pixel's sub-rays summed so far, between the refine's dispatches.
layout(std430, set = 0, binding = PixelSumsBinding) buffer PixelSums { PixelSum pixelSums[]; };

layout(push_constant) uniform MarchPush { MarchWork marchWork; };

float radiance[WAVELENGTHS];
// The body's scattering on the nodes s_k = s_first + k s_step, divided by s:
// sum of w exp(-tau s_k) over the sub-steps (unless EXACT_SCATTERING).
float scatterNodes[SPECTRAL_NODES];
// (550/lambda)^p at the nodes' wavelengths, p the coloured absorption's
// exponent (only with ABSORPTION).
float absorptionNodes[SPECTRAL_NODES];
// What the crossings in front pass of the light from behind them, per bin
// (only with ENERGY_CONSERVATION): the product of their 1 - R(lambda).
float viewTransmittance[WAVELENGTHS];
// The scattering gathered in the Bragg shadow of the round's domain (only
// with ENERGY_CONSERVATION): on nodes like scatterNodes, or per bin with
// EXACT_SCATTERING; flushed through that domain's 1 - R for the light.
float shadowNodes[SPECTRAL_NODES];
float shadowRadiance[WAVELENGTHS];
// The light scattered more than once, gathered like scatterNodes on the
// field's four nodes (only with SCATTERED_LIGHT): the sum of
// mu_s ds (J/s) exp(-tau s) over the sub-steps; the radiance is s^2 times it.
vec4 scatteredNodes;
// (550/lambda)^p at those nodes (only with ABSORPTION).
vec4 scatteredAbsorptionScales;

// The view transmittance of bin l: 1 without ENERGY_CONSERVATION.
float transmittedToEye(int l)
{
  return ENERGY_CONSERVATION ? viewTransmittance[l] : 1.0;
}

// A voxel's absorption at 550 nm, (coloured, grey); 0 without ABSORPTION.
vec2 absorptionAt(int index)
{
  return ABSORPTION ? ABSORPTION_CELL_AT(index) : vec2(0.0);
}

// The absorption's spectral factor at a wavelength of Rayleigh scale s =
// (550/lambda)^4: exp(-coloured depth (550/lambda)^p - grey depth).
float absorbedAt(float s, vec2 tauAbsorption)
{
  return ABSORPTION ? exp(-tauAbsorption.x * pow(s, 0.25 * P.absorptionExponent) - tauAbsorption.y) : 1.0;
}

// The light at a point: optical depths to the light at 550 nm (x the
// scattering; y, z the coloured and grey absorption, 0 without ABSORPTION)
// and the geometry factor.
struct LightSample
{
  vec3 tau;
  float geometry;
};

// Trilinear interpolation of a pair field's four pairs (each a voxel in xy
// and its +x neighbour in zw), f the position within the cell.
vec2 trilinearPairs(vec4 p00, vec4 p10, vec4 p01, vec4 p11, vec3 f)
{
  vec2 x00 = mix(p00.xy, p00.zw, f.x);
  vec2 x10 = mix(p10.xy, p10.zw, f.x);
  vec2 x01 = mix(p01.xy, p01.zw, f.x);
  vec2 x11 = mix(p11.xy, p11.zw, f.x);
  return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

// The light field's and the absorption field's pair at voxel i: its value
// and its +x neighbour's (i as surfaceDistancePair takes it).
vec4 lightFieldPair(int i)
{
  return PAIRED_FIELDS ? LIGHT_FIELD_AT(i) : LIGHT_FIELD_FROM_AT(i);
}

vec4 lightAbsorptionPair(int i)
{
  return PAIRED_FIELDS ? LIGHT_ABSORPTION_AT(i) : LIGHT_ABSORPTION_FROM_AT(i);
}

// The light field of the voxel holding p (NEAREST_LIGHT).
LightSample voxelLightAt(vec3 p)
{
  int v = voxelIndex(clamp(voxelOf(p), ivec3(0), P.gridDimensions - 1));
  vec2 light = PAIRED_FIELDS ? LIGHT_FIELD_AT(v).xy : LIGHT_FIELD_SINGLE_AT(v);
  vec2 absorption = !ABSORPTION ? vec2(0.0) : PAIRED_FIELDS ? LIGHT_ABSORPTION_AT(v).xy : LIGHT_ABSORPTION_SINGLE_AT(v);
  return LightSample(vec3(max(light.x, 0.0), max(absorption, vec2(0.0))), light.y);
}

// The light field at p, trilinear over voxel centres and clamped. Each pair
// holds a voxel and its +x neighbour, so the eight corners take four loads
// (and four more for the absorption). The light pass gives the outside
// corners near the surface values continued from inside. With NEAREST_LIGHT
// (the preview) the voxel's own.
LightSample lightAt(vec3 p)
{
  if (NEAREST_LIGHT) return voxelLightAt(p);
  vec3 g = clamp((p - P.gridOrigin) / P.gridSpacing, vec3(0.0), vec3(P.gridDimensions - 1));
  ivec3 c0 = clamp(ivec3(floor(g)), ivec3(0), max(P.gridDimensions - 2, ivec3(0)));
  ivec3 c1 = min(c0 + 1, P.gridDimensions - 1);
  vec3 f = clamp(g - vec3(c0), 0.0, 1.0);
  int sy = P.gridDimensions.x, sz = P.gridDimensions.x * P.gridDimensions.y;
  int i00 = c0.x + c0.y * sy + c0.z * sz, i10 = c0.x + c1.y * sy + c0.z * sz;
  int i01 = c0.x + c0.y * sy + c1.z * sz, i11 = c0.x + c1.y * sy + c1.z * sz;
  vec2 light = trilinearPairs(lightFieldPair(i00), lightFieldPair(i10), lightFieldPair(i01), lightFieldPair(i11), f);
  vec2 absorption = ABSORPTION
    ? trilinearPairs(lightAbsorptionPair(i00), lightAbsorptionPair(i10), lightAbsorptionPair(i01), lightAbsorptionPair(i11), f)
    : vec2(0.0);
  // Outside voxels beside the opal hold depths continued linearly (negative)
  // from the inside: a read just inside the surface stays at or above 0.
  return LightSample(vec3(max(light.x, 0.0), max(absorption, vec2(0.0))), light.y);
}

// What the march gathers per ray besides the radiance: the brightest
// diffraction's wavelength, luminance and domain, and the first domain the
// refracted ray crosses (the domains are what the edge select compares);
// the crossing being evaluated.
float dominantLambda;
float dominantY;
int dominantDomain;
int firstCrossedDomain;
int crossedDomain;

// What the light passes of the last Bragg shadow evaluated for this pixel
// (passShadow; padded to the shadow table's whole rows), and that shadow's
// domain: a ray leaves and re-enters one domain's shadow, and each
// evaluation costs a crossing's families.
float shadowPassed[4 * SHADOW_ROW_VEC4S];
int shadowPassedDomain;
// The crossing being reflected is lit through a Bragg shadow (passLight).
bool lightShadowed;

// What the light keeps in bin l after the Bragg shadow passLight found: 1
// out of shadows and without ENERGY_CONSERVATION.
float lightKept(int l)
{
  return ENERGY_CONSERVATION && lightShadowed ? shadowPassed[l] : 1.0;
}

// Bin l's share r of the reflected light into the pixel (the coupled-wave R,
// or the paper's band B), times `weight` (lobe or gain), attenuated on the
// light's path and the view's and by the crossings in front; returns its luminance.
float reflectBin(int l, float r, float weight, float tauLight, vec3 tauView, vec2 tauAbsorption)
{
  float s = bins[l].rayleighScale;
  float value = weight * r * exp(-(tauLight + tauView.x) * s) * absorbedAt(s, tauAbsorption) * lightKept(l) *
    transmittedToEye(l);
  radiance[l] += value;
  return value * bins[l].illuminant * bins[l].colourMatching.y * bins[l].width;
}

// The reflected light of one family and order into the pixel; the brightest
// family's lambda_B is the pixel's dominant wavelength.
void reflectFamily(CoupledWaveFamily family, float weight, float tauLight, vec3 tauView, vec2 tauAbsorption)
{
  ivec4 range = coupledWaveBins(family);
  float contributionY = 0.0;
  for (int l = range.x; l <= range.y; ++l)
  {
    if (l < range.z || l > range.w)
    {
      contributionY += reflectBin(l, wingBin(family, l), weight, tauLight, tauView, tauAbsorption);
    }
  }
  for (int l = range.z; l <= range.w; ++l)
  {
    contributionY += reflectBin(l, bandBin(family, l), weight, tauLight, tauView, tauAbsorption);
  }
  if (contributionY > dominantY)
  {
    dominantY = contributionY;
    dominantLambda = family.braggWavelength;
    dominantDomain = crossedDomain;
  }
}

// What the light passes of a Bragg shadow's domain, into shadowPassed, for
// the direction from the domain's centre to the light (the light's direction
// within the cone it sees a domain in, as the Bragg shadow table takes it):
// the domain's row of that table where the light's path there is long enough
// (ShadowTableGroupSize), else evaluated for its length. Evaluated the first
// time the pixel meets that domain's shadow and kept while no other is.
void passShadow(LightShadow shadow)
{
  if (shadow.domain == shadowPassedDomain) return;
  int row = shadow.domain * SHADOW_ROW_VEC4S;
  if (shadow.lengthMm >= shadowTable[row + WAVELENGTHS / 4][WAVELENGTHS % 4])
  {
    // The row in vec4s, the bins and what pads them (opal_render_contract.h).
    [[unroll]] for (int j = 0; j < SHADOW_ROW_VEC4S; ++j)
    {
      vec4 quad = shadowTable[row + j];
      [[unroll]] for (int c = 0; c < 4; ++c) shadowPassed[4 * j + c] = quad[c];
    }
  }
  else
  {
    DomainRecord lattice = domains[shadow.domain];
    passThroughDomain(lattice, normalize(P.light - lattice.centre), shadow.lengthMm);
    for (int l = 0; l < WAVELENGTHS; ++l) shadowPassed[l] = passed[l];
  }
  shadowPassedDomain = shadow.domain;
}

// The light reaching a crossing in the Bragg shadow of another domain keeps
// what that domain passes (lightKept).
void passLight(LightShadow shadow)
{
  lightShadowed = ENERGY_CONSERVATION && shadow.domain >= 0;
  if (lightShadowed) passShadow(shadow);
}

// The view ray's light from behind a crossing keeps what the domain passes.
void dimBehind(DomainRecord lattice, vec3 towardEye, float lengthMm)
{
  passThroughDomain(lattice, towardEye, lengthMm);
  for (int l = 0; l < WAVELENGTHS; ++l) viewTransmittance[l] *= passed[l];
}

// Bragg diffraction at a domain crossing (eq. 4, 9): lambda_B from the
// glancing angle of the light on the lattice planes; the box band B averaged
// per bin; gain G and 1/pi turn the reflected irradiance into radiance.
// tauView: the view path's depths at 550 nm, as LightSample's tau; shadow:
// the domain the light passed before (ENERGY_CONSERVATION); light: the light there.
void diffractAtCrossing(vec3 at, DomainRecord lattice, vec3 towardEye, vec3 tauView, LightShadow shadow, LightSample light)
{
  vec3 towardLight = normalize(P.light - at);
  passLight(shadow);
  float sinGlancing = abs(dot(towardLight, lattice.latticeNormal));
  float tauLight = light.tau.x;
  vec2 tauAbsorption = light.tau.yz + tauView.yz;
  float weight = P.diffractionGain * light.geometry *
    mosaicWeight(lattice.latticeNormal, towardLight, towardEye, P.mosaicSpread) / OPAL_PI;
  for (int k = 1; k <= P.braggOrders; ++k)
  {
    float lambdaB = braggSnellWavelength(lattice.planeSpacing, P.refractiveIndex, sinGlancing, k);
    float contributionY = 0.0;
    // Only the bins about the band (a bin more on either side of those it
    // overlaps, beyond any rounding): every other bin's band is 0, and lavapipe
    // would run the body under a mask for all WAVELENGTHS.
    ivec2 near = binsWithin(lambdaB * vec2(1.0 - 0.5 * P.braggBandwidth, 1.0 + 0.5 * P.braggBandwidth));
    for (int l = max(near.x - 1, 0); l <= min(near.y + 1, WAVELENGTHS - 1); ++l)
    {
      float band = braggBandAverage(bins[l].lambda, bins[l].width, lambdaB, P.braggBandwidth);
      if (band > 0.0)
      {
        contributionY += reflectBin(l, band, weight, tauLight, tauView, tauAbsorption);
      }
    }
    if (contributionY > dominantY)
    {
      dominantY = contributionY;
      dominantLambda = lambdaB;
      dominantDomain = crossedDomain;
    }
  }
  if (ENERGY_CONSERVATION) dimBehind(lattice, towardEye, 0.0);
}

// Coupled-wave Bragg reflection at a crossing (docs/design.md §7.2): per plane
// family and order while lambda_B reaches the shortest bin, R(lambda) of
// N = min(thickness / d, CoherentLayers) layers into a normalised lobe about
// the light's mirror direction, of the light `shadow`'s domain passed; then
// the view ray keeps 1 - R.
void reflectAtCrossing(
  vec3 at, DomainRecord lattice, vec3 towardEye, vec3 tauView, float lengthMm, LightShadow shadow, LightSample light)
{
  vec3 towardLight = normalize(P.light - at);
  passLight(shadow);
  vec2 tauAbsorption = light.tau.yz + tauView.yz;
  float shortest = shortestWavelength();
  for (int f = 0; f < P.latticeFamilies; ++f)
  {
    vec3 normal = familyNormal(lattice, f);
    // The crystal's thickness along the normal: the view ray's path in the
    // domain projected on it (a slab's thickness for planes parallel to it).
    float thicknessMm = lengthMm * abs(dot(towardEye, normal));
    // The lobe about the mirror image of the light's direction in the planes;
    // a family whose lobe misses the eye reflects nothing into this pixel.
    float weight = light.geometry * reflectedLobe(reflect(-towardLight, normal), towardEye, P.mosaicSpread);
    for (int k = 1; weight > 0.0 && k <= 64; ++k)
    {
      CoupledWaveFamily family = coupledFamily(lattice, normal, f, k, towardLight, thicknessMm);
      if (family.braggWavelength < shortest) break;
      reflectFamily(family, weight, light.tau.x, tauView, tauAbsorption);
    }
  }
  dimBehind(lattice, towardEye, lengthMm);
}

// s = (550/lambda)^4 of bin l from the specialisation constants: a constant
// where l is (the unrolled loops).
float binRayleighScale(int l)
{
  float r = 550.0 / (FIRST_WAVELENGTH + float(l) * WAVELENGTH_STEP);
  r *= r;
  return r * r;
}

// The nodes span the wavelength table's s: from the longest wavelength's
// (smallest s) to the shortest's.
float nodeFirst()
{
  return binRayleighScale(WAVELENGTHS - 1);
}

float nodeStep()
{
  return (binRayleighScale(0) - nodeFirst()) / float(SPECTRAL_NODES - 1);
}

// log G of a node's sum, never below LOG_FLOOR (~ log of the smallest
// normal float): in a thick body the sum of a short wavelength's node can
// underflow to 0 (sooner on GPUs that flush denormals), and log 0 = -inf
// times a cubic weight of 0 is NaN (docs/design.md §3.4).
const float LOG_FLOOR = -87.0;
float guardedLog(float g)
{
  return g > 0.0 ? max(log(g), LOG_FLOOR) : LOG_FLOOR;
}

// The nodes' sums G turned into log G in place, once per resampling rather
// than four logs per bin; false (nodes unchanged) where nothing scattered.
// Any node may hold the light: a body that absorbs red (a negative
// absorption exponent) can leave the longest wavelength's sum 0 where the
// blue nodes' are not.
bool nodesToLogs(inout float nodes[SPECTRAL_NODES])
{
  float largest = 0.0;
  for (int k = 0; k < SPECTRAL_NODES; ++k) largest = max(largest, nodes[k]);
  if (!(largest > 0.0))
  {
    return false;
  }
  for (int k = 0; k < SPECTRAL_NODES; ++k) nodes[k] = guardedLog(nodes[k]);
  return true;
}

// The cubic through (0, g.x), (1, g.y), (2, g.z), (3, g.w) at u.
float lagrangeCubic(vec4 g, float u)
{
  return g.x * (u - 1.0) * (u - 2.0) * (u - 3.0) / -6.0 + g.y * u * (u - 2.0) * (u - 3.0) / 2.0 +
    g.z * u * (u - 1.0) * (u - 3.0) / -2.0 + g.w * u * (u - 1.0) * (u - 2.0) / 6.0;
}

// The cubic through four logs at u, limited to their range where one of them
// is the floor: the cubic through a drop to LOG_FLOOR overshoots by ~17 in
// log (e^17) beside it, where the true value lies between the nodes.
// Untouched elsewhere (the presets' images unchanged).
float limitedCubic(vec4 g, float u)
{
  float value = lagrangeCubic(g, u);
  float low = min(min(g.x, g.y), min(g.z, g.w));
  return low <= LOG_FLOOR ? clamp(value, low, max(max(g.x, g.y), max(g.z, g.w))) : value;
}

// The scattering in bin l from log G on the nodes (nodesToLogs): cubic
// Lagrange interpolation of log G through the four nearest nodes (G is a sum
// of decaying exponentials in s, nearly linear in log), times s. In the
// rounds' resampling (flushScattering) the loop over the bins unrolls, so l,
// the nodes and the weights are constants; once per pixel (writePixel) they
// are computed, which builds the pipeline faster (docs/design.md §3.4).
float scatterAt(float logNodes[SPECTRAL_NODES], int l)
{
  float s = binRayleighScale(l);
  float x = (s - nodeFirst()) / nodeStep();
  int i = clamp(int(floor(x)) - 1, 0, SPECTRAL_NODES - 4);
  float u = x - float(i);
  // The four nodes by indices known when the pipeline is built (the loop
  // unrolls over SPECTRAL_NODES, and folds where l is a constant): a read at
  // the index i would keep the nodes in memory, which a CPU driver gathers
  // lane by lane, for every access of the march (docs/design.md §3.4).
  float g0 = 0.0, g1 = 0.0, g2 = 0.0, g3 = 0.0;
  for (int j = 0; j <= SPECTRAL_NODES - 4; ++j)
  {
    bool here = j == i;
    g0 = here ? logNodes[j] : g0;
    g1 = here ? logNodes[j + 1] : g1;
    g2 = here ? logNodes[j + 2] : g2;
    g3 = here ? logNodes[j + 3] : g3;
  }
  return s * exp(limitedCubic(vec4(g0, g1, g2, g3), u));
}

// The light scattered more than once in bin l from the log of its four
// nodes' sums (scatteredNodes), cubic in sqrt(s) (docs/design.md §3.10): s^2
// times the interpolated sum (the field holds J/s).
float scatteredAt(vec4 logNodes, int l)
{
  float s = binRayleighScale(l);
  float first = sqrt(nodeFirst());
  float u = 3.0 * (sqrt(s) - first) / (sqrt(binRayleighScale(0)) - first);
  return s * s * exp(limitedCubic(logNodes, u));
}

// The field's four nodes: sqrt(s) evenly from the longest wavelength's to the
// shortest's (OpalScatteredLight's scatteredLightScales).
vec4 scatteredScales()
{
  float first = sqrt(nodeFirst());
  vec4 roots = first + (sqrt(binRayleighScale(0)) - first) / 3.0 * vec4(0.0, 1.0, 2.0, 3.0);
  return roots * roots;
}

// Rayleigh single scattering (eq. 8) over the ray's segment [t, t + segment]
// in a voxel of coefficients (mus, absorption), isotropic phase 1/(4 pi), in
// sub-steps of at most marchStep with the view transmittance at each
// midpoint; `shadowed`: in the round's Bragg shadow (shadowNodes, shadowRadiance);
// `scattered`: the voxel's light scattered more than once (SCATTERED_LIGHT).
// Returns the view depths (as LightSample's tau) after the segment.
vec3 scatterAlongSegment(vec3 origin, vec3 inward, float t, float segment, float mus, vec2 absorption,
  vec3 tauView, bool shadowed, vec4 scattered)
{
  int pieces = max(1, int(ceil(segment / P.marchStep)));
  float ds = segment / float(pieces);
  for (int q = 0; q < pieces; ++q)
  {
    vec3 at = origin + (t + (float(q) + 0.5) * ds) * inward;
    LightSample light = lightAt(at);
    float tauTotal = light.tau.x + tauView.x + 0.5 * mus * ds;
    vec2 tauAbsorption = light.tau.yz + tauView.yz + 0.5 * absorption * ds;
    // The grey absorption dims every wavelength alike.
    float weight = light.geometry * mus * ds / (4.0 * OPAL_PI) * (ABSORPTION ? exp(-tauAbsorption.y) : 1.0);
    bool coloured = ABSORPTION && tauAbsorption.x > 0.0;
    if (!EXACT_SCATTERING)
    {
      // exp(-tau (s0 + k ds)) = exp(-tau s0) exp(-tau ds)^k: two exps, then
      // products; the coloured absorption, a power of s, one exp per node.
      float term = weight * exp(-tauTotal * nodeFirst());
      float ratio = exp(-tauTotal * nodeStep());
      for (int k = 0; k < SPECTRAL_NODES; ++k)
      {
        float value = coloured ? term * exp(-tauAbsorption.x * absorptionNodes[k]) : term;
        if (ENERGY_CONSERVATION)
        {
          shadowNodes[k] += shadowed ? value : 0.0;
          value = shadowed ? 0.0 : value;
        }
        scatterNodes[k] += value;
        term *= ratio;
      }
    }
    else
    {
      for (int l = 0; l < WAVELENGTHS; ++l)
      {
        float s = bins[l].rayleighScale;
        float value = weight * s * exp(-tauTotal * s) *
          (coloured ? absorbedAt(s, vec2(tauAbsorption.x, 0.0)) : 1.0) * transmittedToEye(l);
        if (ENERGY_CONSERVATION)
        {
          shadowRadiance[l] += shadowed ? value : 0.0;
          value = shadowed ? 0.0 : value;
        }
        radiance[l] += value;
      }
    }
    tauView += vec3(mus, absorption) * ds;
  }
  if (SCATTERED_LIGHT)
  {
    // The scattered light reaches the segment from all around, and the voxel
    // holds one value of it: the view path alone dims it, taken at the
    // segment's midpoint (an optical depth of at most ~0.3 across a voxel:
    // the midpoint rule's error ~0.3%), once per voxel rather than per sub-step.
    vec3 tauMid = tauView - 0.5 * vec3(mus, absorption) * segment;
    vec4 kept = exp(-tauMid.x * scatteredScales());
    if (ABSORPTION) kept *= exp(-tauMid.y * scatteredAbsorptionScales - tauMid.z);
    scatteredNodes += mus * segment * scattered * kept;
  }
  return tauView;
}

// The light scattered more than once gathered since the last flush, into the
// bins through the view transmittance of the crossings in front; restarts.
// Any node may hold the light (nodesToLogs).
void flushScatteredLight()
{
  if (SCATTERED_LIGHT && any(greaterThan(scatteredNodes, vec4(0.0))))
  {
    vec4 logNodes = vec4(guardedLog(scatteredNodes.x), guardedLog(scatteredNodes.y), guardedLog(scatteredNodes.z),
      guardedLog(scatteredNodes.w));
    for (int l = 0; l < WAVELENGTHS; ++l) radiance[l] += transmittedToEye(l) * scatteredAt(logNodes, l);
  }
  scatteredNodes = vec4(0.0);
}

// Domain crossings recorded during the walk and diffracted after it: the
// walk's loop then holds no diffraction (41 bins) that every SIMD lane would
// pay at every voxel; a ray crossing more domains walks on in further rounds.
const int MAX_CROSSINGS = 8;
vec3 crossingPoint[MAX_CROSSINGS];
int crossingDomain[MAX_CROSSINGS];
vec3 crossingDepth[MAX_CROSSINGS]; // view depths at the crossing (as LightSample's tau)
float crossingLength[MAX_CROSSINGS]; // mm of the ray inside the domain (only with COUPLED_WAVE)
LightShadow crossingShadow[MAX_CROSSINGS]; // the light's Bragg shadow there (only with ENERGY_CONSERVATION)
// The light there, read as the crossing is recorded (only FORWARDED): a
// crossing is diffracted at its round's end, which a forwarded ray may reach
// in the next piece, where this piece's light field is not held.
LightSample crossingLight[MAX_CROSSINGS];

// Where the walk stands between rounds.
struct WalkState
{
  VoxelWalk walk;
  float t;
  vec3 tauView;    // depths at 550 nm from P_in along the view path (as LightSample's tau)
  int lastDomain;  // the domain being crossed, counted once
  bool done;       // the ray has left the opal
  LightShadow shadow; // the round's Bragg shadow (ENERGY_CONSERVATION; domain -1: none yet)
};

const LightShadow NO_SHADOW = LightShadow(-1, 0.0, 0.0);

// The Bragg shadow the light pass recorded for voxel v in `domain`: none
// without ENERGY_CONSERVATION or where the recorded domain is v's own.
LightShadow shadowOfVoxel(int v, int domain)
{
  if (!ENERGY_CONSERVATION) return NO_SHADOW;
  LightShadow shadow = LIGHT_SHADOW_AT(v);
  return shadow.domain == domain ? NO_SHADOW : shadow;
}

// The light scattered more than once in voxel v, at `cell`: the light pass
// wrote the field per voxel with the same scatteredLightAt, so both modes
// give the same values (docs/design.md §3.10).
vec4 scatteredLightOf(int v, ivec3 cell)
{
  return SCATTERED_LIGHT_MODE == MarchScatteredLightFromGrid ? scatteredLightAt(cell) : SCATTERED_LIGHT_AT(v);
}

// Whether a cell lies in the forwarded march's piece: layers z in
// marchWork.piece (those beyond the grid in its first or last piece).
bool inMarchPiece(ivec3 cell)
{
  int z = clamp(cell.z, 0, P.gridDimensions.z - 1);
  return z >= marchWork.piece.x && z < marchWork.piece.y;
}

// Whether the forwarded march's piece holds p; the layer of the last point
// asked about, where a paused entry trace goes on (the same rounding as the test).
int askedLayer;
bool surfacePointHeld(vec3 p)
{
  if (!FORWARDED) return true;
  ivec3 cell = voxelOf(p);
  askedLayer = cell.z;
  return inMarchPiece(cell);
}

// The refracted ray being marched: from rayOrigin along rayInward to where it
// leaves the opal (exitTrace); its entry trace while it is not yet entered;
// where its walk stands, in which round, and that round's crossings and steps
// so far (all a forwarded march keeps, keepRay).
vec3 rayOrigin;
vec3 rayInward;
SurfaceTrace entryTrace;
SurfaceTrace exitTrace;
bool rayEntered;
PixelMirror rayMirror; // a forwarded centre ray's, written with its pixel (enterRay)
WalkState walkState;
int walkRound;
int walkCount;
int walkGuard;

// The view ray's traces step at most TraceStepLayers layers z: a forwarded
// march then bisects, and takes the normal at the entry, within
// TraceStepLayers + 2 layers of the piece whose point ended the steps
// (the halo of SurfaceDistance a piece holds), and traces the exit no
// further ahead of its walk (docs/design.md §8.1). Unforwarded the same, so
// that both find the same surface.
TraceRule viewTrace(bool entering)
{
  return TraceRule(entering, 0.05 * P.smallestSpacing, float(TraceStepLayers), entering);
}

// The refracted ray's exit (`exit`, the trace to tEnd of the ray from origin
// along inward), traced only as far as the walk needs it (a forwarded march
// reads SurfaceDistance only near its walk): where it lies, or, while it lies
// beyond `t`, a point before it and beyond t (the trace's last point inside),
// which stands for it in every comparison with t. (The test before the call
// is traceSurfaceOn's own: it spares the walk a call in most cells.)
float exitBeyond(inout SurfaceTrace exit, vec3 origin, vec3 inward, float tEnd, float t)
{
  if (!exit.done && exit.previous <= t) traceSurfaceOn(exit, origin, inward, tEnd, viewTrace(false), t);
  return exit.done ? exit.t : exit.previous;
}

// Walks the refracted ray on from `state`, gathering scattering and
// recording domain crossings (`count` so far in this round, `guard` its
// steps), until it leaves the opal (exitBeyond) or the record is full. False
// where it leaves the forwarded march's piece first: the walk goes on from
// there in the piece it enters, as if never interrupted.
// With ENERGY_CONSERVATION a round records one crossing and ends where the
// ray leaves its domain, so the crossing dims all that lies behind it; it
// gathers scattering in one Bragg shadow besides the unshadowed light, and
// ends before a voxel in another (outside a crossing: inside one, the
// domain's own scattering keeps the round's shadow).
bool walkRecording(inout WalkState state, inout SurfaceTrace exit, inout int count, inout int guard, vec3 origin,
  vec3 inward, float tEnd)
{
  // Unforwarded the exit is traced whole as the ray enters (enterRay);
  // forwarded, a cell at a time, once the cell is known to lie in the piece
  // (1e30 stands for it before). (lavapipe runs a branch's body for every
  // lane, taken or not: a trace called per round, done after the first,
  // cost the unforwarded march ~6%.)
  float tExit = FORWARDED ? 1e30 : exit.t;
  for (; guard < 65536 && state.t < tExit && (ENERGY_CONSERVATION || count < MAX_CROSSINGS); ++guard)
  {
    if (FORWARDED && !inMarchPiece(state.walk.cell)) return false;
    if (FORWARDED) tExit = exitBeyond(exit, origin, inward, tEnd, cellExit(state.walk));
    float tNext = min(cellExit(state.walk), tExit);
    float segment = tNext - state.t;
    if (segment > 0.0 && insideGrid(state.walk.cell))
    {
      int v = voxelIndex(state.walk.cell);
      VoxelCell cell = VOXEL_CELL_AT(v);
      int domain = cell.domainId;
      float mus = cell.scattering;
      vec2 absorption = absorptionAt(v);
      if (ENERGY_CONSERVATION && count == 1 && domain != state.lastDomain) break;
      LightShadow shadow = shadowOfVoxel(v, domain);
      bool otherShadow = shadow.domain >= 0 && state.shadow.domain >= 0 && shadow.domain != state.shadow.domain;
      if (ENERGY_CONSERVATION && count == 0 && otherShadow) break;
      if (shadow.domain >= 0 && state.shadow.domain < 0) state.shadow = shadow;
      if (domain >= 0 && domain != state.lastDomain)
      {
        // The paper's domains neither scatter nor absorb; beyond it they may
        // (docs/design.md §2.10): the depths at the segment's midpoint.
        crossingPoint[count] = origin + (state.t + 0.5 * segment) * inward;
        crossingDomain[count] = domain;
        if (firstCrossedDomain < 0) firstCrossedDomain = domain;
        crossingDepth[count] = state.tauView + 0.5 * segment * vec3(mus, absorption);
        if (COUPLED_WAVE) crossingLength[count] = 0.0;
        crossingShadow[count] = shadow;
        if (FORWARDED) crossingLight[count] = lightAt(crossingPoint[count]);
        ++count;
      }
      if (COUPLED_WAVE && domain >= 0 && count > 0) crossingLength[count - 1] += segment;
      if (mus > 0.0)
      {
        state.tauView = scatterAlongSegment(origin, inward, state.t, segment, mus, absorption, state.tauView,
          shadow.domain >= 0, SCATTERED_LIGHT ? scatteredLightOf(v, state.walk.cell) : vec4(0.0));
      }
      else if (ABSORPTION)
      {
        state.tauView.yz += absorption * segment;
      }
      state.lastDomain = domain;
    }
    state.t = tNext;
    if (state.t >= tExit) break;
    stepWalk(state.walk);
  }
  // Not done where a crossing, a shadow or a full record interrupted the walk.
  state.done = state.t >= tExit || guard == 65536;
  return true;
}

// The body's scattering gathered in a round, into the bins through the view
// transmittance of the crossings in front of it, the part in the round's
// Bragg shadow through what its domain passes of the light; the nodes restart
// (ENERGY_CONSERVATION: the scattering behind the next crossing is dimmed by it).
void flushScattering(inout WalkState state)
{
  bool shadowed = state.shadow.domain >= 0;
  if (shadowed) passShadow(state.shadow);
  bool open = !EXACT_SCATTERING && nodesToLogs(scatterNodes);
  bool behind = shadowed && !EXACT_SCATTERING && nodesToLogs(shadowNodes);
  [[unroll]] for (int l = 0; l < WAVELENGTHS; ++l)
  {
    float lit = (open ? scatterAt(scatterNodes, l) : 0.0) + (behind ? shadowPassed[l] * scatterAt(shadowNodes, l) : 0.0);
    radiance[l] += viewTransmittance[l] * lit + (shadowed && EXACT_SCATTERING ? shadowPassed[l] * shadowRadiance[l] : 0.0);
    shadowRadiance[l] = 0.0;
  }
  for (int k = 0; k < SPECTRAL_NODES; ++k)
  {
    scatterNodes[k] = 0.0;
    shadowNodes[k] = 0.0;
  }
  flushScatteredLight();
  state.shadow = NO_SHADOW;
}

// The refracted ray voxel by voxel on from where it stands to where it leaves
// the opal, gathering scattering and each domain once per crossing; false
// where it leaves the forwarded march's piece first.
bool marchOn()
{
  // Locals while it walks (the walk's loop on private globals was ~5% slower on lavapipe).
  WalkState state = walkState;
  SurfaceTrace exit = exitTrace;
  int round = walkRound, count = walkCount, guard = walkGuard;
  vec3 origin = rayOrigin, inward = rayInward;
  // Where the ray leaves the grid's box, where a forwarded exit trace ends (unforwarded, unused).
  float tEnd = FORWARDED ? gridBoxHits(origin, inward).y : 0.0;
  for (; round < 4096 && !state.done; ++round)
  {
    if (!walkRecording(state, exit, count, guard, origin, inward, tEnd))
    {
      walkState = state;
      exitTrace = exit;
      walkRound = round;
      walkCount = count;
      walkGuard = guard;
      return false;
    }
    if (ENERGY_CONSERVATION) flushScattering(state);
    for (int c = 0; c < count; ++c)
    {
      crossedDomain = crossingDomain[c];
      LightSample light = FORWARDED ? crossingLight[c] : lightAt(crossingPoint[c]);
      if (COUPLED_WAVE)
      {
        reflectAtCrossing(crossingPoint[c], domains[crossingDomain[c]], -inward, crossingDepth[c], crossingLength[c],
          crossingShadow[c], light);
      }
      else
      {
        diffractAtCrossing(
          crossingPoint[c], domains[crossingDomain[c]], -inward, crossingDepth[c], crossingShadow[c], light);
      }
    }
    count = 0;
    guard = 0;
  }
  return true;
}

// The absorption's spectral factors at the nodes, which follow the frame.
void setRayScales()
{
  if (ABSORPTION && !EXACT_SCATTERING)
  {
    for (int k = 0; k < SPECTRAL_NODES; ++k)
    {
      absorptionNodes[k] = pow(nodeFirst() + float(k) * nodeStep(), 0.25 * P.absorptionExponent);
    }
  }
  if (SCATTERED_LIGHT && ABSORPTION)
  {
    scatteredAbsorptionScales = pow(scatteredScales(), vec4(0.25 * P.absorptionExponent));
  }
}

// Empties what the march gathers along one ray.
void resetRay()
{
  for (int l = 0; l < WAVELENGTHS; ++l) radiance[l] = 0.0;
  if (ENERGY_CONSERVATION)
  {
    for (int l = 0; l < WAVELENGTHS; ++l) viewTransmittance[l] = 1.0;
  }
  for (int k = 0; k < SPECTRAL_NODES; ++k) scatterNodes[k] = 0.0;
  if (ENERGY_CONSERVATION)
  {
    for (int k = 0; k < SPECTRAL_NODES; ++k) shadowNodes[k] = 0.0;
    for (int l = 0; l < WAVELENGTHS; ++l) shadowRadiance[l] = 0.0;
    shadowPassedDomain = -1;
    lightShadowed = false;
  }
  setRayScales();
  scatteredNodes = vec4(0.0);
  dominantLambda = 0.0;
  dominantY = 0.0;
  dominantDomain = -1;
  firstCrossedDomain = -1;
}

// A forwarded ray's words in keptStates (opal_kept_state.glsl): the layer its
// walk stands in, or its entry trace's next point (the piece that takes it
// up), KeptDone once its pixel has it, KeptUnwritten once it finished in a
// shared march; then what keepRay keeps.
const int RAY_WORDS = RAY_STATE_WORDS(WAVELENGTHS, SPECTRAL_NODES);

void keepWalk()
{
  keepVoxelWalk(walkState.walk, rayInward);
  keepFloat(walkState.t);
  keepVec3(walkState.tauView);
  keepInt(walkState.lastDomain);
  keepBool(walkState.done);
  keepShadow(walkState.shadow);
  keepInt(walkRound);
  keepInt(walkCount);
  keepInt(walkGuard);
  for (int c = 0; c < MAX_CROSSINGS; ++c)
  {
    keepVec3(crossingPoint[c]);
    keepInt(crossingDomain[c]);
    keepVec3(crossingDepth[c]);
    keepFloat(crossingLength[c]);
    keepShadow(crossingShadow[c]);
    keepVec3(crossingLight[c].tau);
    keepFloat(crossingLight[c].geometry);
  }
}

void keepSum(inout PixelSum sum)
{
  keepVec3(sum.xyz);
  keepFloat(sum.depth);
  keepFloat(sum.dominantLambda);
  keepFloat(sum.dominantY);
  keepInt(sum.dominantDomain);
  keepInt(sum.hits);
  keepInt(sum.firstDomainSeen);
  keepInt(sum.brightestDomainSeen);
  keepInt(sum.alike);
}

// Energy conservation's sums (the view transmittance, the scattering in the
// round's Bragg shadow) and the last Bragg shadow evaluated.
void keepShadowedSums()
{
  for (int l = 0; l < WAVELENGTHS; ++l)
  {
    keepFloat(viewTransmittance[l]);
    keepFloat(shadowRadiance[l]);
  }
  for (int k = 0; k < SPECTRAL_NODES; ++k) keepFloat(shadowNodes[k]);
  keepInt(shadowPassedDomain);
  for (int l = 0; l < 4 * SHADOW_ROW_VEC4S; ++l) keepFloat(shadowPassed[l]);
}

// Saves (`saving`) or restores the ray of invocation `slot` of a forwarded
// march: everything its march reads again, bit for bit, so that a ray
// forwarded between pieces is marched step for step as one never forwarded
// (one layout both ways), the last Bragg shadow evaluated included (its
// value follows the path length it was first met with, not its domain
// alone). The absorption's node factors are evaluated again. A ray still
// tracing its entry keeps only that trace and its pixel's sums (15 words):
// entering sets the rest. A ray kept has entered once its entry trace is
// done (one that missed finished), at the trace's distance.
void keepRay(int slot, bool saving, inout PixelSum sum, inout float tHit, inout float transmitted)
{
  beginKeeping(slot, RAY_WORDS, saving);
  keepTrace(entryTrace);
  keepSum(sum);
  rayEntered = entryTrace.done;
  if (!rayEntered) return;
  tHit = entryTrace.t;
  keepFloat(transmitted);
  keepVec3(rayMirror.nearLight);
  keepInt(rayMirror.valid);
  keepVec3(rayOrigin);
  keepVec3(rayInward);
  keepTrace(exitTrace);
  keepWalk();
  keepFloat(dominantLambda);
  keepFloat(dominantY);
  keepInt(dominantDomain);
  keepInt(firstCrossedDomain);
  keepFloat(scatteredNodes.x);
  keepFloat(scatteredNodes.y);
  keepFloat(scatteredNodes.z);
  keepFloat(scatteredNodes.w);
  for (int l = 0; l < WAVELENGTHS; ++l) keepFloat(radiance[l]);
  for (int k = 0; k < SPECTRAL_NODES; ++k) keepFloat(scatterNodes[k]);
  if (ENERGY_CONSERVATION) keepShadowedSums(); // else never read
  if (!saving) setRayScales();
}

// A forwarded march's ray taken up again by a later dispatch: false where its
// pixel has it already or it traces or walks on in another piece (one word read).
bool resumeRay(int slot, inout PixelSum sum, out float tHit, out float transmitted)
{
  tHit = 0.0;
  transmitted = 0.0;
  uint layer = keptLayer(slot, RAY_WORDS);
  if (!keptGoesOn(layer) || !inMarchPiece(ivec3(0, 0, int(layer)))) return false;
  keepRay(slot, false, sum, tHit, transmitted);
  return true;
}

// Whether a marched sub-ray met the opal, where (its distance from the eye),
// and the share 1 - F it carries out.
struct RayHit
{
  bool hit;
  float tHit;
  float transmitted;
};

// A shared march's ray that finished, kept (`saving`) until the dispatch
// that writes the finished rays' pixels restores it (docs/design.md §8.1):
// all keepRay keeps and whether it met the opal.
void keepFinishedRay(int slot, bool saving, inout PixelSum sum, inout RayHit met)
{
  keepRay(slot, saving, sum, met.tHit, met.transmitted);
  keepBool(met.hit);
}

// In the dispatch that writes a shared march's finished rays' pixels, the
// ray of `slot` restored where it finished (KeptUnwritten); false for any other.
bool takeUpFinished(int slot, inout PixelSum sum, out RayHit met)
{
  met = RayHit(false, 0.0, 0.0);
  if (keptLayer(slot, RAY_WORDS) != KeptUnwritten) return false;
  keepFinishedRay(slot, false, sum, met);
  return true;
}

// The pixels the march writes: the rectangle's, then (for the edge select)
// the ring of pixels around it, row y = -1, row y = height, column x = -1,
// column x = width. The index of pixel `local` (in the rectangle's
// coordinates) among them.
int storedPixel(ivec2 local)
{
  ivec2 size = P.rectSize;
  if (all(greaterThanEqual(local, ivec2(0))) && all(lessThan(local, size))) return local.x + size.x * local.y;
  int ring = size.x * size.y;
  if (local.y < 0) return ring + local.x + 1;
  if (local.y >= size.y) return ring + size.x + 2 + local.x + 1;
  return ring + 2 * (size.x + 2) + (local.x < 0 ? 0 : size.y) + local.y;
}

// The ring's pixel `item` (storedPixel's inverse); false beyond the ring.
bool ringPixel(int item, out ivec2 local)
{
  ivec2 size = P.rectSize;
  int row = size.x + 2;
  if (item < 2 * row)
  {
    local = ivec2(item % row - 1, item < row ? -1 : size.y);
    return true;
  }
  item -= 2 * row;
  local = ivec2(item < size.y ? -1 : size.x, item % size.y);
  return item < 2 * size.y;
}

// What enterRay found of a primary ray: the opal (its refracted ray ready to
// march), no opal, or (forwarded) the next point of its entry trace in another piece.
const int RAY_ENTERED = 1, RAY_MISSED = 0, RAY_PAUSED = -1;

// Traces the primary ray through `pixel` (image coordinates) to the opal,
// from the grid's box (`fresh`) or on from entryTrace. Entered: its distance to the surface (tHit) and the
// share 1 - F of the light it carries out (transmitted), its refracted ray
// ready to march (marchOn). With `mirror` >= 0 it records where its mirror
// image passes the light (for the highlight pass): at that pixel, or
// forwarded in rayMirror, written with the pixel (unforwarded the value
// is not held through the march: holding it, fig12's march at 320 x 240
// took ~3.5% longer on lavapipe, docs/design.md §8.1).
int enterRay(vec2 pixel, int mirror, bool fresh, out float tHit, out float transmitted)
{
  vec3 eye = P.eye;
  vec3 direction = primaryDirection(pixel);
  vec2 box = gridBoxHits(eye, direction);
  tHit = -1.0;
  transmitted = 0.0;
  if (fresh) entryTrace = surfaceTrace(box.x); // not done where the box is missed (a shared march keeps it)
  if (box.x > box.y) return RAY_MISSED;
  if (!traceSurfaceOn(entryTrace, eye, direction, box.y, viewTrace(true), 1e30)) return RAY_PAUSED;
  tHit = entryTrace.t;
  if (tHit < 0.0) return RAY_MISSED;
  resetRay();
  // P_in: Fresnel reflection of the light and refraction of the view ray (paper §6.1).
  vec3 entry = eye + tHit * direction;
  vec3 normal = surfaceNormal(entry);
  float cosI = clamp(-dot(direction, normal), 0.0, 1.0);
  float mu = P.refractiveIndex;
  transmitted = 1.0 - fresnelReflectance(cosI, mu);
  if (mirror >= 0)
  {
    float cosMirror;
    vec4 near = mirrorPointNearLight(entry, direction, normal, cosMirror);
    rayMirror = PixelMirror(near.xyz, int(near.w));
    if (!FORWARDED) pixelMirror[mirror] = rayMirror;
  }
  vec3 inward = refract(direction, normal, 1.0 / mu);
  rayOrigin = entry - 1e-4 * P.smallestSpacing * normal;
  rayInward = inward;
  exitTrace = surfaceTrace(0.0);
  if (!FORWARDED) traceSurfaceOn(exitTrace, rayOrigin, inward, gridBoxHits(rayOrigin, inward).y, viewTrace(false), 1e30);
  rayEntered = true;
  walkState = WalkState(startWalk(rayOrigin, inward), 0.0, vec3(0.0), -1, false, NO_SHADOW);
  walkRound = 0;
  walkCount = 0;
  walkGuard = 0;
  return RAY_ENTERED;
}

// The layer z a forwarded ray goes on in: its walk's, or its entry trace's next point's.
int rayLayer()
{
  return clamp(rayEntered ? walkState.walk.cell.z : askedLayer, 0, P.gridDimensions.z - 1);
}

// Adds a marched ray, `weight` of the pixel. Spectral radiance: the light's
// normalised D65 scales every term; the view ray carries 1 - F out of the
// opal (the highlight pass adds the mirrored light). The pixel's first ray
// to meet the opal writes its spectrum (where it keeps one), the others add to it.
void addRay(int pixelIndex, bool spectrum, float transmitted, float weight, float tHit, inout PixelSum sum)
{
  if (!EXACT_SCATTERING && nodesToLogs(scatterNodes))
  {
    for (int l = 0; l < WAVELENGTHS; ++l) radiance[l] += scatterAt(scatterNodes, l);
  }
  flushScatteredLight();
  float scale = transmitted * weight;
  for (int l = 0; l < WAVELENGTHS; ++l)
  {
    float value = scale * radiance[l] * bins[l].illuminant;
    sum.xyz += value * bins[l].colourMatching * bins[l].width;
    if (spectrum)
    {
      int at = pixelIndex * WAVELENGTHS + l;
      pixelSpectrum[at] = sum.hits == 0 ? value : pixelSpectrum[at] + value;
    }
  }
  sum.depth = sum.hits == 0 ? tHit : min(sum.depth, tHit);
  if (dominantY * transmitted > sum.dominantY)
  {
    sum.dominantY = dominantY * transmitted;
    sum.dominantLambda = dominantLambda;
    sum.dominantDomain = dominantDomain;
  }
  ++sum.hits;
}

void writeMiss(int pixelIndex, bool spectrum, bool centre)
{
  pixelColour[pixelIndex] = PixelColour(vec3(0.0), 0.0);
  pixelBragg[pixelIndex] = PixelBragg(0.0, -1, 0.0, -1);
  if (centre) pixelMirror[pixelIndex] = PixelMirror(vec3(0.0), 0);
  if (spectrum)
  {
    for (int l = 0; l < WAVELENGTHS; ++l) pixelSpectrum[pixelIndex * WAVELENGTHS + l] = 0.0;
  }
}

// Writes the pixel from the sums of its `rays` rays (1: its centre ray;
// docs/design.md §3.4): XYZ and spectrum the area's mean (a missed sub-ray
// adds nothing), depth the nearest, the dominant wavelength (and its domain)
// the brightest ray's, coverage the share that meets the opal, and the first
// domain crossed: the centre ray's (`firstDomain` >= -2 keeps the pixel's).
void writePixel(int pixelIndex, bool spectrum, PixelSum sum, int rays, bool centre, int firstDomain)
{
  if (sum.hits == 0)
  {
    writeMiss(pixelIndex, spectrum, centre);
    return;
  }
  if (firstDomain < -1) firstDomain = pixelBragg[pixelIndex].firstDomain;
  pixelColour[pixelIndex] = PixelColour(sum.xyz, sum.depth);
  pixelBragg[pixelIndex] =
    PixelBragg(sum.dominantLambda, sum.dominantDomain, float(sum.hits) / float(rays), firstDomain);
}

// The row of first-stage sub-ray t < n on a pixel's n x n grid: one per
// column and row, spread ((2t + t / (n/2)) mod n for even n, 2t mod n for odd).
int firstStageRow(int t, int n)
{
  return n % 2 == 0 ? (2 * t + t / max(n / 2, 1)) % n : (2 * t) % n;
}

// The cell of sub-ray t on a pixel's n x n grid (docs/design.md §3.4): the
// first n one per column and row, the others row by row.
ivec2 subRayCell(int t, int n)
{
  if (t < n) return ivec2(t, firstStageRow(t, n));
  int k = t - n, y = k / (n - 1), x = k % (n - 1);
  int taken = 0; // the column of row y's first-stage sub-ray
  for (int c = 0; c < n; ++c)
  {
    if (firstStageRow(c, n) == y) taken = c;
  }
  return ivec2(x < taken ? x : x + 1, y);
}

// Notes what the first-stage sub-ray t saw: whether it met the opal, its
// first and brightest domains.
void noteFirstStage(inout PixelSum sum, bool hit, int t)
{
  int first = hit ? firstCrossedDomain : -2, brightest = hit ? dominantDomain : -2;
  if (t == 0)
  {
    sum.firstDomainSeen = first;
    sum.brightestDomainSeen = brightest;
    return;
  }
  sum.alike = sum.alike != 0 && first == sum.firstDomainSeen && brightest == sum.brightestDomainSeen ? 1 : 0;
}

// The first stage's n sub-rays, weighted 1/n, become n of n x n: 1/n^2,
// their sums as the second stage's first sub-ray starts, and the pixel's
// spectrum as that sub-ray's is added (where its pixel is written: in a
// shared march on every share, docs/design.md §8.1).
void reweighFirstStage(int n, inout PixelSum sum)
{
  sum.xyz /= float(n);
}

void reweighFirstSpectrum(int pixelIndex, bool spectrum, int n, PixelSum sum)
{
  if (!spectrum || sum.hits == 0) return;
  for (int l = 0; l < WAVELENGTHS; ++l) pixelSpectrum[pixelIndex * WAVELENGTHS + l] /= float(n);
}

// Neighbours whose surfaces lie farther apart in depth than this many times
// their spacing across the view mark a slope steeper than ~76 degrees, where
// a pixel's rays meet the surface at a stretch of depths and the body's
// chord changes fast: refined like an edge.
const float EDGE_SLOPE = 4.0;

// Whether an edge lies between the centre rays of the stored pixels a and b,
// `spacing` apart across the view at their depth: one meets the opal and the
// other not (the outline), or they cross a different first domain or draw
// their brightest diffraction from a different one, or the surface between
// them is steep.
const int NO_EDGE = 0, INNER_EDGE = 1, OUTLINE = 2;

int edgeBetween(int a, int b, float pixelAngle)
{
  PixelBragg p = pixelBragg[a], q = pixelBragg[b];
  if ((p.coverage > 0.0) != (q.coverage > 0.0)) return OUTLINE;
  if (p.coverage == 0.0) return NO_EDGE;
  float depthA = pixelColour[a].depth, depthB = pixelColour[b].depth;
  bool inner = p.firstDomain != q.firstDomain || p.dominantDomain != q.dominantDomain ||
    abs(depthA - depthB) > EDGE_SLOPE * pixelAngle * max(depthA, depthB);
  return inner ? INNER_EDGE : NO_EDGE;
}

// A queued pixel's entry: its index, and the top bit where the outline
// crosses it (its coverage takes every sub-ray: a first stage that all met
// the opal, or all missed it, misses the slivers the outline cuts).
const uint OUTLINE_BIT = 0x80000000u;

// Queues the pixel `local` of the rectangle where an edge lies between its
// centre ray and one of its eight neighbours' (the ring's beyond the
// rectangle, so that a piece of the image selects as the whole image does).
void selectEdge(ivec2 local)
{
  int pixelIndex = storedPixel(local);
  float pixelAngle = 2.0 * P.tanHalfViewAngle / float(P.imageHeight);
  int edge = NO_EDGE;
  for (int k = 0; k < 9 && edge != OUTLINE; ++k)
  {
    ivec2 offset = ivec2(k % 3, k / 3) - 1;
    if (k != 4) edge = max(edge, edgeBetween(pixelIndex, storedPixel(local + offset), pixelAngle * length(vec2(offset))));
  }
  if (edge != NO_EDGE)
  {
    edgePixels[atomicAdd(edgeQueue[0].count, 1u)] = uint(pixelIndex) | (edge == OUTLINE ? OUTLINE_BIT : 0u);
  }
}

// This invocation's item among the dispatch's, for the 1-D passes over a
// queue or the ring.
int marchItem()
{
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  return int(group * uint(MarchGroupSide * MarchGroupSide) + gl_LocalInvocationIndex);
}

// The pixel queued for the refine's `stage` at this invocation's item: false
// beyond the dispatch's items or the queue; else the pixel (in the rectangle),
// its place among the select's queued pixels, and whether the outline crosses it.
bool queuedPixel(int stage, out ivec2 local, out int item, out bool outline)
{
  local = ivec2(0);
  outline = false;
  int rectPixels = P.rectSize.x * P.rectSize.y;
  item = marchWork.first + marchItem();
  if (item >= marchWork.first + marchWork.count || item >= int(edgeQueue[stage].count)) return false;
  if (stage == 1) item = int(edgePixels[rectPixels + item]);
  uint entry = edgePixels[item];
  int queued = int(entry & ~OUTLINE_BIT);
  local = ivec2(queued % P.rectSize.x, queued / P.rectSize.x);
  outline = (entry & OUTLINE_BIT) != 0u;
  return true;
}

// Sub-ray `index` of the n x n of the pixel `local` (n = 1: its centre ray):
// the pixel's index among those stored and whether the outline crosses it.
struct SubRay
{
  ivec2 local;
  int pixelIndex;
  int n;
  int index;
  bool outline;
};

// `ray` started and marched (its pixel's sums so far in `sum`), or in a
// forwarded march's later dispatch taken up again: false where it finished
// before or traces or walks on in another piece (saved for it), or in a
// shared march finishes (kept until its pixel is written, takeUpFinished);
// else where it met the opal (`met`).
bool marchSubRay(SubRay ray, inout PixelSum sum, out RayHit met)
{
  int slot = marchItem();
  int started = FORWARDED ? marchWork.resumed : MarchStartsRays;
  bool resumed = started == MarchResumesRays;
  bool last = FORWARDED && marchWork.last != 0;
  if (started == MarchWritesFinished) return takeUpFinished(slot, sum, met);
  if (resumed)
  {
    if (!resumeRay(slot, sum, met.tHit, met.transmitted))
    {
      countUnfinished(slot, RAY_WORDS, last);
      return false;
    }
  }
  else
  {
    if (ray.outline) sum.alike = 0;
    if (ray.index == ray.n) reweighFirstStage(ray.n, sum);
    rayEntered = false;
  }
  vec2 at = vec2(P.rectOrigin + ray.local) + (vec2(subRayCell(ray.index, ray.n)) + 0.5) / float(ray.n);
  int entry =
    rayEntered ? RAY_ENTERED : enterRay(at, ray.n == 1 ? ray.pixelIndex : -1, !resumed, met.tHit, met.transmitted);
  met.hit = entry == RAY_ENTERED;
  // Unforwarded, marchOn always finishes: the constant folds the keeping away.
  bool paused = met.hit ? !marchOn() : entry == RAY_PAUSED;
  if (FORWARDED && paused)
  {
    keepLayer(slot, RAY_WORDS, uint(rayLayer()));
    keepRay(slot, true, sum, met.tHit, met.transmitted);
    countUnfinished(slot, RAY_WORDS, last);
    return false;
  }
  if (FORWARDED && marchWork.sharesRays != 0)
  {
    keepLayer(slot, RAY_WORDS, KeptUnwritten);
    keepFinishedRay(slot, true, sum, met);
    return false;
  }
  if (FORWARDED) keepLayer(slot, RAY_WORDS, KeptDone);
  return true;
}

// One march of a ray (marchSubRay) for every mode: the march's code is then built once.
// MarchPixels and MarchRing march a pixel's centre ray; MarchRefineEdges one
// sub-ray of a queued pixel per dispatch (lavapipe ends all of an
// invocation's loops once they have run 65535 iterations together: n x n
// whole marches in one invocation would reach it), its sums kept between:
// first n sub-rays, one per row and column, which stand for the pixel where
// they all see the same (the same first and brightest domains; never where
// the outline crosses it), then for the others, queued anew so that the second
// stage's dispatches cover only them, the rest of the n x n grid.
void main()
{
  ivec2 local;
  int mode = marchWork.mode, item = 0, n = 1, subRay = 0;
  bool outline = false;
  if (mode == MarchRefineEdges)
  {
    n = P.pixelSamples;
    subRay = marchWork.subRay;
    if (!queuedPixel(subRay < n ? 0 : 1, local, item, outline)) return;
  }
  else if (mode == MarchRing)
  {
    if (!ringPixel(marchItem(), local)) return;
  }
  else
  {
    local = ivec2(gl_GlobalInvocationID.xy) + marchWork.origin; // within the rectangle
    if (local.x >= P.rectSize.x || local.y >= P.rectSize.y) return;
    if (mode == MarchSelectEdges)
    {
      selectEdge(local);
      return;
    }
  }
  int pixelIndex = storedPixel(local);
  bool centre = n == 1, spectrum = P.writeSpectrum != 0 && pixelIndex < P.rectSize.x * P.rectSize.y;
  PixelSum sum = PixelSum(vec3(0.0), 0.0, 0.0, 0.0, -1, 0, -2, -2, 1);
  if (subRay > 0) sum = pixelSums[item]; // not a ?:, whose mixed struct types glslang stores invalidly
  RayHit met;
  if (!marchSubRay(SubRay(local, pixelIndex, n, subRay, outline), sum, met)) return;
  if (subRay == n) reweighFirstSpectrum(pixelIndex, spectrum, n, sum);
  if (met.hit) addRay(pixelIndex, spectrum, met.transmitted, 1.0 / float(subRay < n ? n : n * n), met.tHit, sum);
  if (FORWARDED && met.hit && centre) pixelMirror[pixelIndex] = rayMirror;
  if (!centre && subRay < n) noteFirstStage(sum, met.hit, subRay);
  bool settled = subRay + 1 == n * n || (subRay + 1 == n && sum.alike != 0);
  if (!centre) pixelSums[item] = sum;
  if (!settled && subRay + 1 == n)
  {
    edgePixels[P.rectSize.x * P.rectSize.y + int(atomicAdd(edgeQueue[1].count, 1u))] = uint(item);
  }
  if (!settled) return;
  writePixel(pixelIndex, spectrum, sum, subRay + 1, centre, centre ? (met.hit ? firstCrossedDomain : -1) : -2);
}
