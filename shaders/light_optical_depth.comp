#version 450
// LightOpticalDepthPass (DESIGN.md §3, "the main speed-up"): for every voxel,
// the optical depth at 550 nm along the straight line to the light, and the
// light's geometric factor there: Fresnel transmission at the light's entry
// point L_in times the inverse-square fall-off, normalised to 1 at the apex.
// Absorption is 0 and mu_s is proportional to lambda^-4, so every wavelength
// follows as tau(lambda) = tau(550) (550/lambda)^4; this replaces the paper's
// march towards the light at every sample and wavelength (eq. 6, 7).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "opal_render_layout.glsl"
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"

layout(std430, set = 0, binding = 5) writeonly buffer LightOpticalDepthField { float lightOpticalDepth[]; };
layout(std430, set = 0, binding = 6) writeonly buffer LightGeometryField { float lightGeometry[]; };

layout(push_constant) uniform SlabRange { int firstVoxel; int voxelCount; } slab;

void main()
{
  int local = int(gl_GlobalInvocationID.x);
  if (local >= slab.voxelCount)
  {
    return;
  }
  int index = slab.firstVoxel + local;
  int nx = P.gridDims.x, ny = P.gridDims.y;
  ivec3 c = ivec3(index % nx, (index / nx) % ny, index / (nx * ny));
  vec3 p = voxelCentre(c);
  vec3 toLight = P.light.xyz - p;
  float distanceToLight = length(toLight);
  vec3 direction = toLight / distanceToLight;
  float apexDistance2 = P.lighting.x;
  float mu = P.optics.x;

  if (surfaceDistance(p) > 0.0)
  {
    // Outside the opal: unattenuated light.
    lightOpticalDepth[index] = 0.0;
    lightGeometry[index] = apexDistance2 / (distanceToLight * distanceToLight);
    return;
  }
  // March towards the light, one sample per voxel length at the midpoints,
  // until the path leaves the opal at L_in (eq. 7, absorption 0).
  float h = P.gridOrigin.w;
  float tau = 0.0;
  float t = 0.0;
  float tEnd = min(gridBoxHits(p, direction).y, distanceToLight);
  float entry = tEnd;
  for (int i = 0; i < 65536 && t < tEnd; ++i)
  {
    float step = min(h, tEnd - t);
    vec3 mid = p + (t + 0.5 * step) * direction;
    if (surfaceDistance(p + (t + step) * direction) > 0.0)
    {
      // The path leaves the opal within this step: find L_in, count the inside part.
      float a = t, b = t + step;
      for (int k = 0; k < 12; ++k)
      {
        float m = 0.5 * (a + b);
        if (surfaceDistance(p + m * direction) > 0.0) b = m; else a = m;
      }
      entry = a;
      mid = p + 0.5 * (t + entry) * direction;
      ivec3 v = voxelOf(mid);
      if (insideGrid(v))
      {
        tau += scatteringField[voxelIndex(v)] * (entry - t);
      }
      break;
    }
    ivec3 v = voxelOf(mid);
    if (insideGrid(v))
    {
      tau += scatteringField[voxelIndex(v)] * step;
    }
    t += step;
  }
  vec3 lightEntry = p + entry * direction;
  float transmission = 1.0 - fresnelReflectance(dot(surfaceNormal(lightEntry), direction), mu);
  // DESIGN.md §3: 1/r^2 to the sample; the paper's eq. 6 stops it at L_in (an option).
  float r = P.lighting.z > 0.5 ? distance(P.light.xyz, lightEntry) : distanceToLight;
  lightOpticalDepth[index] = tau;
  lightGeometry[index] = transmission * apexDistance2 / (r * r);
}
