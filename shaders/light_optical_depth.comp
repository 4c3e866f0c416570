#version 450
// LightOpticalDepthPass (docs/design.md §3.3): for every voxel,
// the optical depth at 550 nm along the straight line to the light, and the
// light's geometric factor there: Fresnel transmission at the light's entry
// point L_in times the inverse-square fall-off, normalised to 1 at the apex.
// Absorption is 0 and mu_s is proportional to lambda^-4, so every wavelength
// follows as tau(lambda) = tau(550) (550/lambda)^4; this replaces the paper's
// march towards the light at every sample and wavelength (eq. 6, 7).
// With the light above the grid, a sweep layer by layer from the top makes it
// O(1) per voxel (LightPassSweepFromAbove); the few voxels the light enters
// within their step are queued and lit by a dispatch of their own
// (LightPassEnterFromAbove), so the sweep carries none of that work, which a
// CPU driver would pay for every voxel. Otherwise each voxel marches to the
// light (LightPassMarchTowardsLight). The mode is a specialisation constant:
// each pipeline holds only its own mode's code.
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = LightPassGroupSize) in;
layout(constant_id = 0) const int LIGHT_PASS_MODE = LightPassSweepFromAbove;
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"

layout(std430, set = 0, binding = LightFieldBinding) buffer LightField { LightFieldPair lightField[]; };

layout(std430, set = 0, binding = LightEntryQueuesBinding) buffer LightEntryQueues { DispatchQueue queues[]; };
layout(std430, set = 0, binding = LightEntryVoxelsBinding) buffer LightEntryVoxels { uint entryVoxels[]; };

layout(push_constant) uniform LightPassPush { LightPassWork work; };


// The light's geometric factor at p, given where its path enters the opal:
// Fresnel transmission there times the inverse-square fall-off, 1 at the apex.
// docs/design.md §4.1: 1/r^2 to the sample; the paper's eq. 6 stops it at L_in (an option).
float entryGeometry(vec3 p, vec3 lightEntry, vec3 direction)
{
  float transmission = 1.0 - fresnelReflectance(dot(surfaceNormal(lightEntry), direction), P.refractiveIndex);
  float r = P.lightFalloffAtEntry != 0 ? distance(P.light, lightEntry) : distance(P.light, p);
  return transmission * P.apexDistanceSquared / (r * r);
}

// Stores a voxel's optical depth and geometry factor where the light field
// keeps them: in its own pair, and as the +x neighbour in the pair before it
// (in its own pair too at the end of a row).
void storeLight(int index, float opticalDepth, float geometry)
{
  vec2 light = vec2(opticalDepth, geometry);
  int x = index % P.gridDimensions.x;
  lightField[index].voxel = light;
  if (x > 0) lightField[index - 1].nextVoxel = light;
  if (x == P.gridDimensions.x - 1) lightField[index].nextVoxel = light;
}

float scatteringAt(vec3 p)
{
  ivec3 v = voxelOf(p);
  return insideGrid(v) ? scatteringField[voxelIndex(v)] : 0.0;
}

// LightPassMarchTowardsLight: march towards the light, one sample per voxel length at the midpoints,
// until the path leaves the opal at L_in (eq. 7, absorption 0).
void marchTowardsLight(int index, vec3 p, vec3 direction, float distanceToLight)
{
  float h = P.smallestSpacing;
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
        entry = bisectSurface(p, direction, t + step, t);
        tau += scatteringAt(p + 0.5 * (t + entry) * direction) * (entry - t);
        break;
      }
      safe = t + step - 0.9 * d;
    }
    tau += scatteringAt(p + (t + 0.5 * step) * direction) * step;
    t += step;
  }
  storeLight(index, tau, entryGeometry(p, p + entry * direction, direction));
}

// LightPassSweepFromAbove: the path from p to the light crosses the plane of the layer above
// at q; the optical depth and geometry there are interpolated from that
// layer (over its voxels inside the opal only, so the outside's unattenuated
// values do not leak in) and the short segment p-q is added. O(1) per voxel.
void sweepFromLayerAbove(int index, ivec3 c, vec3 p, vec3 direction)
{
  float step = P.gridSpacing.y / direction.y;
  vec3 q = p + step * direction;
  bool topLayer = c.y == P.gridDimensions.y - 1;
  // q lies in the plane of the layer above's centres: bilinear there in x, z.
  ivec3 layerAbove = ivec3(0, min(c.y + 1, P.gridDimensions.y - 1), 0);
  vec2 g = clamp((q.xz - P.gridOrigin.xz) / P.gridSpacing.xz, vec2(0.0), vec2(P.gridDimensions.xz - 1));
  ivec2 c0 = clamp(ivec2(floor(g)), ivec2(0), max(P.gridDimensions.xz - 2, ivec2(0)));
  ivec2 c1 = min(c0 + 1, P.gridDimensions.xz - 1);
  vec2 f = clamp(g - vec2(c0), 0.0, 1.0);
  int corners[4];
  float weights[4];
  float distanceQ = 0.0;
  for (int corner = 0; corner < 4; ++corner)
  {
    corners[corner] = voxelIndex(ivec3((corner & 1) != 0 ? c1.x : c0.x, layerAbove.y, (corner & 2) != 0 ? c1.y : c0.y));
    weights[corner] = ((corner & 1) != 0 ? f.x : 1.0 - f.x) * ((corner & 2) != 0 ? f.y : 1.0 - f.y);
    distanceQ += weights[corner] * surfaceDistanceField[corners[corner]];
  }
  if (topLayer)
  {
    // Above the grid the surface distance continues linearly (the opal may
    // reach the grid's top face): use that, not the top layer's own values.
    distanceQ = surfaceDistance(q);
  }
  if (distanceQ > 0.0)
  {
    // The light enters the opal between p and q: queued for LightPassEnterFromAbove.
    int layerSize = P.gridDimensions.x * P.gridDimensions.z;
    uint slot = atomicAdd(queues[c.y].count, 1u);
    entryVoxels[c.y * layerSize + int(slot)] = uint(index);
    if (slot % uint(LightPassGroupSize) == 0u)
    {
      atomicAdd(queues[c.y].groupsX, 1u);
    }
    return;
  }
  float tau = 0.0, geometry = 0.0, weightSum = 0.0;
  float tauAll = 0.0, geometryAll = 0.0;
  // The corners' light: two pairs, each a corner and its +x neighbour.
  LightFieldPair nearZ = lightField[corners[0]], farZ = lightField[corners[2]];
  vec2 cornerLight[4] = vec2[4](nearZ.voxel, nearZ.nextVoxel, farZ.voxel, farZ.nextVoxel);
  for (int corner = 0; corner < 4; ++corner)
  {
    int vi = corners[corner];
    float w = weights[corner];
    float inside = surfaceDistanceField[vi] <= 0.0 ? w : 0.0;
    float tauCorner = cornerLight[corner].x;
    float geometryCorner = cornerLight[corner].y;
    tau += inside * tauCorner;
    geometry += inside * geometryCorner;
    weightSum += inside;
    tauAll += w * tauCorner;
    geometryAll += w * geometryCorner;
  }
  float tauQ = weightSum > 1e-6 ? tau / weightSum : tauAll;
  float geometryQ = weightSum > 1e-6 ? geometry / weightSum : geometryAll;
  // Two half-segments, each with the scattering of the voxel it lies in.
  int below = voxelIndex(c);
  // Along one light path the Fresnel factor is constant: rescale the fall-off from q to p.
  float rq = distance(P.light, q), rp = distance(P.light, p);
  storeLight(index, tauQ + 0.5 * step * (scatteringField[below] + scatteringAt(p + 0.75 * step * direction)),
    P.lightFalloffAtEntry != 0 ? geometryQ : geometryQ * (rq * rq) / (rp * rp));
}

// LightPassEnterFromAbove: a queued voxel whose path to the light enters the
// opal within one layer's step: its part of the path up to the entry point.
void enterFromAbove(int index, vec3 p, vec3 direction)
{
  float step = P.gridSpacing.y / direction.y;
  float entry = bisectSurface(p, direction, step, 0.0);
  storeLight(index, scatteringAt(p + 0.5 * entry * direction) * entry,
    entryGeometry(p, p + entry * direction, direction));
}

// The voxel this invocation lights, or -1.
int voxelOfInvocation()
{
  int nx = P.gridDimensions.x, ny = P.gridDimensions.y;
  int local = int(gl_GlobalInvocationID.x);
  if (LIGHT_PASS_MODE == LightPassMarchTowardsLight)
  {
    return local < work.count ? work.first + local : -1;
  }
  if (LIGHT_PASS_MODE == LightPassEnterFromAbove)
  {
    int layerSize = nx * P.gridDimensions.z;
    return local < int(queues[work.layer].count) ? int(entryVoxels[work.layer * layerSize + local]) : -1;
  }
  return local < nx * P.gridDimensions.z ? local % nx + nx * (work.layer + ny * (local / nx)) : -1;
}

void main()
{
  int index = voxelOfInvocation();
  if (index < 0) return;
  int nx = P.gridDimensions.x, ny = P.gridDimensions.y;
  ivec3 c = ivec3(index % nx, (index / nx) % ny, index / (nx * ny));
  vec3 p = voxelCentre(c);
  vec3 toLight = P.light - p;
  float distanceToLight = length(toLight);
  vec3 direction = toLight / distanceToLight;
  if (LIGHT_PASS_MODE == LightPassEnterFromAbove)
  {
    enterFromAbove(index, p, direction);
    return;
  }
  // A voxel centre: its own SurfaceDistance, no interpolation needed.
  if (surfaceDistanceField[index] > 0.0)
  {
    // Outside the opal: unattenuated light.
    storeLight(index, 0.0, P.apexDistanceSquared / (distanceToLight * distanceToLight));
    return;
  }
  if (LIGHT_PASS_MODE == LightPassMarchTowardsLight)
  {
    marchTowardsLight(index, p, direction, distanceToLight);
  }
  else
  {
    sweepFromLayerAbove(index, c, p, direction);
  }
}
