// Reads of the voxel fields: nearest voxel for the model's piecewise-constant
// values (scattering coefficient, domain id), trilinear for the smooth ones
// (surface distance, light optical depth and geometry), clamped at the edges.

#include "opal_volume_addresses.glsl"

// SurfaceDistance of each voxel and of its +x neighbour (the last voxel of a
// row repeats its own): a trilinear read takes four loads instead of eight,
// and surface tracing is most of what a pixel reads. Without PAIRED_FIELDS
// (PairedFields in the contract: only fields read by address, whose pass
// defines PAIRED_FIELDS_CONSTANT, its own constant id) the same buffer holds
// each voxel's own value only; bound fields are always paired, and their
// unpaired accessors read the pair.
#ifdef OPAL_VOLUME_ADDRESSES
layout(constant_id = PAIRED_FIELDS_CONSTANT) const bool PAIRED_FIELDS = true;
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer VoxelCellRef { VoxelCell value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SurfaceDistanceRef { vec2 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SurfaceDistanceSingleRef { float value; };
#define VOXEL_CELL_AT(i) VoxelCellRef(voxelAddress(volumeAddresses.voxelCells, (i), 8u)).value
#define SURFACE_DISTANCE_AT(i) SurfaceDistanceRef(voxelAddress(volumeAddresses.surfaceDistance, (i), 8u)).value
#define SURFACE_DISTANCE_SINGLE_AT(i) SurfaceDistanceSingleRef(voxelAddress(volumeAddresses.surfaceDistance, (i), 4u)).value
// Unpaired, the two floats from voxel i on: its value and the next voxel's, one load.
#define SURFACE_DISTANCE_FROM_AT(i) SurfaceDistanceRef(voxelAddress(volumeAddresses.surfaceDistance, (i), 4u)).value
#else
layout(std430, set = 0, binding = VoxelCellBinding) readonly buffer VoxelCells { VoxelCell voxelCells[]; };
layout(std430, set = 0, binding = SurfaceDistanceBinding) readonly buffer SurfaceDistanceField { vec2 surfaceDistancePairs[]; };
const bool PAIRED_FIELDS = true;
#define VOXEL_CELL_AT(i) voxelCells[mediumIndex(i)]
#define SURFACE_DISTANCE_AT(i) surfaceDistancePairs[mediumIndex(i)]
#define SURFACE_DISTANCE_SINGLE_AT(i) surfaceDistancePairs[mediumIndex(i)].x
#define SURFACE_DISTANCE_FROM_AT(i) surfaceDistancePairs[mediumIndex(i)]
#endif

// The highlight pass reads SurfaceDistance from its tiles alone (SURFACE_TILES).
#ifdef SURFACE_TILES
#ifdef OPAL_VOLUME_ADDRESSES
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SurfaceTileRef { SurfaceTile value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SurfaceTileValueRef { float value; };
#define SURFACE_TILE_AT(i) SurfaceTileRef(voxelAddress(volumeAddresses.surfaceTiles, (i), 8u)).value
#define SURFACE_TILE_VALUE_AT(i) SurfaceTileValueRef(voxelAddress(volumeAddresses.surfaceTileValues, (i), 4u)).value
#else
layout(std430, set = 0, binding = SurfaceTileBinding) readonly buffer SurfaceTileField { SurfaceTile surfaceTiles[]; };
layout(std430, set = 0, binding = SurfaceTileValuesBinding) readonly buffer SurfaceTileValueField { float surfaceTileValues[]; };
#define SURFACE_TILE_AT(i) surfaceTiles[i]
#define SURFACE_TILE_VALUE_AT(i) surfaceTileValues[i]
#endif
#endif

// A voxel's index. A grid holds up to 2^32 - 1 voxels (docs/design.md
// §3.7), beyond int's range: an index's bits are read unsigned (voxelAddress,
// voxelOfIndex), its int wrapping past 2^31, and -1 (2^32 - 1) is no voxel.
int voxelIndex(ivec3 c)
{
  return c.x + P.gridDimensions.x * (c.y + P.gridDimensions.y * c.z);
}

// A voxel's place in a bound field that may hold a piece (the light fields,
// the every-order field): its index less the piece's first voxel
// (P.heldFirstVoxel, 0 where addressed; docs/design.md §8.1).
int heldIndex(int index)
{
  return index - P.heldFirstVoxel;
}

// The same for the medium's cells, absorption cells and SurfaceDistance (P.mediumFirstVoxel).
int mediumIndex(int index)
{
  return index - P.mediumFirstVoxel;
}

// The voxel of index `index` (its bits unsigned, as voxelIndex says).
ivec3 voxelOfIndex(int index)
{
  uint i = uint(index), nx = uint(P.gridDimensions.x), ny = uint(P.gridDimensions.y);
  return ivec3(i % nx, (i / nx) % ny, i / (nx * ny));
}

bool insideGrid(ivec3 c)
{
  return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, P.gridDimensions));
}

// The voxel whose cell [centre - spacing/2, centre + spacing/2) holds p.
ivec3 voxelOf(vec3 p)
{
  return ivec3(floor((p - P.gridOrigin) / P.gridSpacing + 0.5));
}

vec3 voxelCentre(ivec3 c)
{
  return P.gridOrigin + vec3(c) * P.gridSpacing;
}


// A voxel's own SurfaceDistance (no interpolation at a centre).
float voxelSurfaceDistance(int index)
{
  return PAIRED_FIELDS ? SURFACE_DISTANCE_AT(index).x : SURFACE_DISTANCE_SINGLE_AT(index);
}

// SurfaceDistance of voxel i and of its +x neighbour, as a pair holds them,
// where i is not the last voxel of its row (no interpolation's lower corner
// is; rows of one voxel are always paired): unpaired, the next voxel's.
// (No division: finding a row's end by a modulo per read made the unpaired
// march ~1.8x the paired one on lavapipe.)
vec2 surfaceDistancePair(int i)
{
  return PAIRED_FIELDS ? SURFACE_DISTANCE_AT(i) : SURFACE_DISTANCE_FROM_AT(i);
}

// The trilinear mix of a cell's corners, as pairs along x.
float cellMix(vec2 p00, vec2 p10, vec2 p01, vec2 p11, vec3 f)
{
  return mix(mix(mix(p00.x, p00.y, f.x), mix(p10.x, p10.y, f.x), f.y),
    mix(mix(p01.x, p01.y, f.x), mix(p11.x, p11.y, f.x), f.y), f.z);
}

#ifdef SURFACE_TILES
// The cell of corners c0, c1 read from its tile (SurfaceTile): the held
// tile's own values, which are the field's, or the tile's bound.
float tiledCellValue(ivec3 c0, ivec3 c1, vec3 f)
{
  const int side = SurfaceTileCells + 1;
  ivec3 tile = c0 / SurfaceTileCells;
  ivec3 tiles = (max(P.gridDimensions - 1, ivec3(1)) + SurfaceTileCells - 1) / SurfaceTileCells;
  SurfaceTile t = SURFACE_TILE_AT(tile.x + tiles.x * (tile.y + tiles.y * tile.z));
  if (t.slot < 0) return t.bound;
  ivec3 a = c0 - tile * SurfaceTileCells, b = c1 - tile * SurfaceTileCells;
  int base = t.slot * side * side * side;
  int r00 = base + side * (a.y + side * a.z), r10 = base + side * (b.y + side * a.z);
  int r01 = base + side * (a.y + side * b.z), r11 = base + side * (b.y + side * b.z);
  return cellMix(vec2(SURFACE_TILE_VALUE_AT(r00 + a.x), SURFACE_TILE_VALUE_AT(r00 + b.x)),
    vec2(SURFACE_TILE_VALUE_AT(r10 + a.x), SURFACE_TILE_VALUE_AT(r10 + b.x)),
    vec2(SURFACE_TILE_VALUE_AT(r01 + a.x), SURFACE_TILE_VALUE_AT(r01 + b.x)),
    vec2(SURFACE_TILE_VALUE_AT(r11 + a.x), SURFACE_TILE_VALUE_AT(r11 + b.x)), f);
}
#endif

// SurfaceDistance trilinear over voxel centres; within half a cell beyond
// the outermost centres (up to the grid's box) the outermost cells'
// interpolant continues linearly. Clamped there, the field's value at the
// lowest centres plus the distance to them cut a chamfer half a cell high
// under the rim, where the dome meets the base y = 0: the silhouette's
// pixels came out 1-2% dark (docs/design.md §3.3). With SURFACE_TILES read
// from the tiles, else from the field.
float trilinearSurfaceDistance(vec3 position)
{
  vec3 g = clamp((position - P.gridOrigin) / P.gridSpacing, vec3(-0.5), vec3(P.gridDimensions) - 0.5);
  ivec3 c0 = clamp(ivec3(floor(g)), ivec3(0), max(P.gridDimensions - 2, ivec3(0)));
  ivec3 c1 = min(c0 + 1, P.gridDimensions - 1);
  vec3 f = g - vec3(c0);
#ifdef SURFACE_TILES
  return tiledCellValue(c0, c1, f);
#else
  int sy = P.gridDimensions.x, sz = P.gridDimensions.x * P.gridDimensions.y;
  return cellMix(surfaceDistancePair(c0.x + c0.y * sy + c0.z * sz), surfaceDistancePair(c0.x + c1.y * sy + c0.z * sz),
    surfaceDistancePair(c0.x + c0.y * sy + c1.z * sz), surfaceDistancePair(c0.x + c1.y * sy + c1.z * sz), f);
#endif
}

// SurfaceDistance, continued beyond the grid's box by the distance to it
// (the opal touches the grid's top and sides; a clamped field there would
// flatten the surface's gradient and hide the apex).
float surfaceDistance(vec3 p)
{
  vec3 lo = P.gridOrigin - 0.5 * P.gridSpacing;
  vec3 nearest = clamp(p, lo, lo + vec3(P.gridDimensions) * P.gridSpacing);
  return trilinearSurfaceDistance(nearest) + distance(p, nearest);
}

// Outward unit normal of the smooth surface: the gradient of SurfaceDistance.
vec3 surfaceNormal(vec3 p)
{
  vec3 h = P.gridSpacing;
  vec3 g = vec3(surfaceDistance(p + vec3(h.x, 0, 0)) - surfaceDistance(p - vec3(h.x, 0, 0)),
    surfaceDistance(p + vec3(0, h.y, 0)) - surfaceDistance(p - vec3(0, h.y, 0)),
    surfaceDistance(p + vec3(0, 0, h.z)) - surfaceDistance(p - vec3(0, 0, h.z))) / (2.0 * h);
  float len = length(g);
  return len > 0.0 ? g / len : vec3(0.0, 1.0, 0.0);
}

// Entry and exit distances of a ray with the grid's box; tNear > tFar if it misses.
vec2 gridBoxHits(vec3 origin, vec3 direction)
{
  vec3 lo = P.gridOrigin - 0.5 * P.gridSpacing;
  vec3 hi = lo + vec3(P.gridDimensions) * P.gridSpacing;
  vec3 inverse = 1.0 / direction;
  vec3 t0 = (lo - origin) * inverse;
  vec3 t1 = (hi - origin) * inverse;
  vec3 tMin = min(t0, t1);
  vec3 tMax = max(t0, t1);
  return vec2(max(max(tMin.x, tMin.y), max(tMin.z, 0.0)), min(min(tMax.x, tMax.y), tMax.z));
}

// The zero of SurfaceDistance along a ray between a point outside (at
// outsideT) and one inside (at insideT), by bisection; returns the inside end.
float bisectSurface(vec3 origin, vec3 direction, float outsideT, float insideT)
{
  for (int k = 0; k < 12; ++k)
  {
    float m = 0.5 * (outsideT + insideT);
    if (surfaceDistance(origin + m * direction) > 0.0) outsideT = m; else insideT = m;
  }
  return insideT;
}

// A trace of SurfaceDistance's first zero along a ray, by sphere tracing and
// then bisection: an entry (from outside in) or an exit (from inside out).
// Its steps can stop and go on: a forwarded march's ray goes on in the piece
// its next point lies in (docs/design.md §8.1).
struct SurfaceTrace
{
  float t;        // the next point to read; once done, the zero (an entry's -1: none; an exit's: tEnd at most)
  float previous; // the last point read on the side the trace started
  int steps;      // points read
  bool done;
};

// How a trace steps: which way it crosses, its least step (mm), the most
// layers z a step may pass (0: any; the view's traces, so that a forwarded
// march bisects and takes the normal near the point that ended the steps),
// and whether it may stop before a point SURFACE_POINT_HELD does not hold.
struct TraceRule
{
  bool entering;
  float minStep;
  float stepLayers;
  bool pausable;
};

// Whether SurfaceDistance at p is read here: everywhere but in a forwarded
// march, which defines it before this file.
#ifndef SURFACE_POINT_HELD
#define SURFACE_POINT_HELD(p) true
#endif

SurfaceTrace surfaceTrace(float tStart)
{
  return SurfaceTrace(tStart, tStart, 0, false);
}

// Steps `s` on (at most 1024 points entering, 4096 leaving, and with a
// bound on the steps' layers as many more as it can take across the grid's
// layers) until it is done, or, pausable, its next point is not held here
// (false), or its last point on its starting side lies beyond `limit` (an
// exit traced only as far as a walk needs it: the zero lies beyond that
// point; 1e30: no limit, which the compiler folds away).
bool traceSurfaceOn(inout SurfaceTrace s, vec3 origin, vec3 direction, float tEnd, TraceRule rule, float limit)
{
  if (s.done) return true;
  bool bounded = rule.stepLayers > 0.0;
  float longest = bounded ? rule.stepLayers * P.gridSpacing.z / max(abs(direction.z), 1e-20) : 1e30;
  int most = (rule.entering ? 1024 : 4096) + (bounded ? int(float(P.gridDimensions.z) / rule.stepLayers) + 1 : 0);
  // The bisection after the loop, not in it: lavapipe would run it under a
  // mask at every step (docs/design.md §3.4).
  bool crossed = false;
  for (; s.steps < most && s.t <= tEnd; ++s.steps)
  {
    if (limit < 1e30 && s.previous > limit) return true;
    vec3 p = origin + s.t * direction;
    if (rule.pausable && !SURFACE_POINT_HELD(p)) return false;
    float d = surfaceDistance(p);
    if (rule.entering ? d <= 0.0 : d > 0.0)
    {
      crossed = true;
      break;
    }
    s.previous = s.t;
    s.t += min(max(rule.entering ? 0.9 * d : -0.9 * d, rule.minStep), longest);
  }
  if (crossed)
  {
    // The bisection's outside end first: the last point for an entry, this one for an exit.
    float outside = rule.entering ? s.previous : s.t, inside = rule.entering ? s.t : s.previous;
    s.t = bisectSurface(origin, direction, outside, inside);
  }
  else
  {
    s.t = rule.entering ? -1.0 : min(s.t, tEnd);
  }
  s.done = true;
  return true;
}

// First zero of SurfaceDistance along the ray in [tStart, tEnd] going from
// outside (positive) to inside, in steps of at least minStep (of any
// length); -1 if none.
float traceSurfaceEntry(vec3 origin, vec3 direction, float tStart, float tEnd, float minStep)
{
  SurfaceTrace s = surfaceTrace(tStart);
  traceSurfaceOn(s, origin, direction, tEnd, TraceRule(true, minStep, 0.0, false), 1e30);
  return s.t;
}
