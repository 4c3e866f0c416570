#version 450
// LightOpticalDepthPass (DESIGN.md §3, "the main speed-up"): for every voxel,
// the optical depth at 550 nm along the straight line to the light, and the
// light's geometric factor there: Fresnel transmission at the light's entry
// point L_in times the inverse-square fall-off, normalised to 1 at the apex.
// Absorption is 0 and mu_s is proportional to lambda^-4, so every wavelength
// follows as tau(lambda) = tau(550) (550/lambda)^4; this replaces the paper's
// march towards the light at every sample and wavelength (eq. 6, 7). (A sweep
// layer by layer from the top, O(1) per voxel, was tried: its repeated
// interpolation biased the blue end by up to ~17% per pixel against the
// reference renderer, so each voxel marches.)
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 256) in;

#include "opal_render_layout.glsl"
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"

layout(std430, set = 0, binding = 5) writeonly buffer LightOpticalDepthField { float lightOpticalDepth[]; };
layout(std430, set = 0, binding = 6) writeonly buffer LightGeometryField { float lightGeometry[]; };

// The voxels [first, first + count) this dispatch covers.
layout(push_constant) uniform Work { int first; int count; } work;

float apexDistance2() { return P.lighting.x; }

// Where the path from p towards the light (unit direction) leaves the opal
// within distance `span`: bisection on SurfaceDistance (positive there).
float opalExit(vec3 p, vec3 direction, float lo, float hi)
{
  for (int k = 0; k < 12; ++k)
  {
    float m = 0.5 * (lo + hi);
    if (surfaceDistance(p + m * direction) > 0.0) hi = m; else lo = m;
  }
  return lo;
}

// The light's geometric factor at p, given where its path enters the opal:
// Fresnel transmission there times the inverse-square fall-off, 1 at the apex.
// DESIGN.md §3: 1/r^2 to the sample; the paper's eq. 6 stops it at L_in (an option).
float entryGeometry(vec3 p, vec3 lightEntry, vec3 direction)
{
  float transmission = 1.0 - fresnelReflectance(dot(surfaceNormal(lightEntry), direction), P.optics.x);
  float r = P.lighting.z > 0.5 ? distance(P.light.xyz, lightEntry) : distance(P.light.xyz, p);
  return transmission * apexDistance2() / (r * r);
}

float scatteringAt(vec3 p)
{
  ivec3 v = voxelOf(p);
  return insideGrid(v) ? scatteringField[voxelIndex(v)] : 0.0;
}

// March towards the light, one sample per voxel length at the midpoints,
// until the path leaves the opal at L_in (eq. 7, absorption 0).
void marchTowardsLight(int index, vec3 p, vec3 direction, float distanceToLight)
{
  float h = P.gridOrigin.w;
  float tau = 0.0;
  float t = 0.0;
  float tEnd = min(gridBoxHits(p, direction).y, distanceToLight);
  float entry = tEnd;
  // The path cannot leave the opal within the surface distance of a point on
  // it (a distance field changes at most as fast as one moves): test for the
  // exit only beyond the distance known to be safe, as sphere tracing does.
  float safe = 0.0;
  for (int i = 0; i < 65536 && t < tEnd; ++i)
  {
    float step = min(h, tEnd - t);
    if (t + step > safe)
    {
      float d = surfaceDistance(p + (t + step) * direction);
      if (d > 0.0)
      {
        entry = opalExit(p, direction, t, t + step);
        tau += scatteringAt(p + 0.5 * (t + entry) * direction) * (entry - t);
        break;
      }
      safe = t + step - 0.9 * d;
    }
    tau += scatteringAt(p + (t + 0.5 * step) * direction) * step;
    t += step;
  }
  lightOpticalDepth[index] = tau;
  lightGeometry[index] = entryGeometry(p, p + entry * direction, direction);
}

void main()
{
  int local = int(gl_GlobalInvocationID.x);
  if (local >= work.count)
  {
    return;
  }
  int index = work.first + local;
  int nx = P.gridDims.x, ny = P.gridDims.y;
  ivec3 c = ivec3(index % nx, (index / nx) % ny, index / (nx * ny));
  vec3 p = voxelCentre(c);
  vec3 toLight = P.light.xyz - p;
  float distanceToLight = length(toLight);
  vec3 direction = toLight / distanceToLight;
  // A voxel centre: its own SurfaceDistance, no interpolation needed.
  if (surfaceDistanceField[index] > 0.0)
  {
    // Outside the opal: unattenuated light.
    lightOpticalDepth[index] = 0.0;
    lightGeometry[index] = apexDistance2() / (distanceToLight * distanceToLight);
    return;
  }
  marchTowardsLight(index, p, direction, distanceToLight);
}
