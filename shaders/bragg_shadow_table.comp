#version 450
// BraggShadowTablePass (docs/design.md §7.2): per domain, what it passes of
// the light per wavelength bin, for the direction from its centre to the light
// and a path long enough that every family's N is CoherentLayers, with that
// path's least length. The march reads a domain's row for each Bragg shadow
// a view ray meets instead of evaluating its families there; it evaluates
// only shadows whose path is shorter.
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = ShadowTableGroupSize) in;
layout(constant_id = ShadowTableWavelengthsConstant) const int WAVELENGTHS = 41;
layout(constant_id = ShadowTableCoupledWaveConstant) const bool COUPLED_WAVE = false;

#include "opal_optics.glsl"
#include "opal_coupled_wave.glsl"
#include "opal_bragg_transmission.glsl"

layout(std430, set = 0, binding = DomainTableBinding) readonly buffer DomainTable { DomainRecord domains[]; };
layout(std430, set = 0, binding = ShadowTableBinding) writeonly buffer ShadowTable { vec4 shadowTable[]; };
const int ROW_VEC4S = SHADOW_TABLE_ROW_VEC4S(WAVELENGTHS);

// A path (mm) longer than any domain's: every family's N is CoherentLayers.
const float SATURATING_LENGTH_MM = 1e6;

// The least length (mm) of a path along `ray` that crosses CoherentLayers
// layers of every family whose first order reaches the bins: N d / |ray . n|
// (coupledFamily's thickness over the path's share along the normal), a
// hair longer against rounding; 0 in the paper's model.
float saturationLength(DomainRecord lattice, vec3 ray)
{
  if (!COUPLED_WAVE) return 0.0;
  float shortest = shortestWavelength(), longest = 0.0;
  for (int f = 0; f < P.latticeFamilies; ++f)
  {
    vec3 normal = familyNormal(lattice, f);
    float along = abs(dot(ray, normal));
    CoupledWaveFamily family = coupledFamily(lattice, normal, f, 1, ray, SATURATING_LENGTH_MM * along);
    if (family.braggWavelength >= shortest) longest = max(longest, family.thickness * 1e-6 / along);
  }
  return 1.0001 * longest;
}

void main()
{
  int domain = passItem(ShadowTableGroupSize);
  if (domain >= P.domainCount) return;
  DomainRecord lattice = domains[domain];
  vec3 towardLight = normalize(P.light - lattice.centre);
  passThroughDomain(lattice, towardLight, SATURATING_LENGTH_MM);
  float saturation = saturationLength(lattice, towardLight);
  // The row's floats: the bins, the saturation length, zeros (opal_render_contract.h).
  for (int j = 0; j < ROW_VEC4S; ++j)
  {
    vec4 quad = vec4(0.0);
    for (int c = 0; c < 4; ++c)
    {
      int l = 4 * j + c;
      quad[c] = l < WAVELENGTHS ? passed[min(l, WAVELENGTHS - 1)] : (l == WAVELENGTHS ? saturation : 0.0);
    }
    shadowTable[domain * ROW_VEC4S + j] = quad;
  }
}
