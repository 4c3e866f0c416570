// A 3-D DDA over the voxel cells (Amanatides & Woo): the view march's
// refracted ray and the light pass's path to the light cross the
// piecewise-constant fields cell by cell, with each cell's exact length.
// Needs opal_volume_fields.glsl (voxelOf).

// The current cell and the ray distances to its next boundary along each
// axis; the steps (setWalkSteps) follow from the direction alone.
struct VoxelWalk
{
  ivec3 cell;
  ivec3 stepDir;
  vec3 tMax;
  vec3 tDelta;
};

// A walk from `origin` along `direction`. Its steps as setWalkSteps sets
// them, written out (below): the two must stay the same, bit for bit.
VoxelWalk startWalk(vec3 origin, vec3 direction)
{
  VoxelWalk walk;
  vec3 cellLow = P.gridOrigin - 0.5 * P.gridSpacing;
  walk.cell = voxelOf(origin);
  walk.stepDir = ivec3(sign(direction));
  vec3 inverse = 1.0 / max(abs(direction), vec3(1e-20));
  vec3 nextBoundary = cellLow + (vec3(walk.cell) + max(vec3(walk.stepDir), vec3(0.0))) * P.gridSpacing;
  walk.tMax = (nextBoundary - origin) * inverse * sign(direction);
  walk.tMax = mix(walk.tMax, vec3(1e30), equal(walk.stepDir, ivec3(0)));
  walk.tDelta = P.gridSpacing * inverse;
  return walk;
}

// The steps of a walk along `direction`, as startWalk sets them, bit for
// bit: a forwarded walk keeps only its cell and tMax (keepVoxelWalk) and
// sets these again as it is taken up (TestOpalForwardedMarch: its images
// would differ). startWalk does not call this: the light pass took ~4%
// longer on lavapipe where it did, its code otherwise the same.
void setWalkSteps(inout VoxelWalk walk, vec3 direction)
{
  walk.stepDir = ivec3(sign(direction));
  walk.tDelta = P.gridSpacing * (1.0 / max(abs(direction), vec3(1e-20)));
}

// The distance along the ray to the current cell's exit.
float cellExit(VoxelWalk walk)
{
  return min(min(walk.tMax.x, walk.tMax.y), walk.tMax.z);
}

// Steps to the next voxel along the axis whose boundary comes first.
void stepWalk(inout VoxelWalk walk)
{
  if (walk.tMax.x <= walk.tMax.y && walk.tMax.x <= walk.tMax.z) { walk.cell.x += walk.stepDir.x; walk.tMax.x += walk.tDelta.x; }
  else if (walk.tMax.y <= walk.tMax.z) { walk.cell.y += walk.stepDir.y; walk.tMax.y += walk.tDelta.y; }
  else { walk.cell.z += walk.stepDir.z; walk.tMax.z += walk.tDelta.z; }
}
