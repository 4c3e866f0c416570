#version 450
// LightOpticalDepthPass (docs/design.md §3.3): for every voxel,
// the optical depth at 550 nm along the straight line to the light, and the
// light's geometric factor there: Fresnel transmission at the light's entry
// point L_in times the inverse-square fall-off, normalised to 1 at the apex.
// Absorption is 0 and mu_s is proportional to lambda^-4, so every wavelength
// follows as tau(lambda) = tau(550) (550/lambda)^4; this replaces the paper's
// march towards the light at every sample and wavelength (eq. 6, 7).
// With ABSORPTION (docs/design.md §3.9) the paths also sum the absorption,
// coloured and grey apart (they scale differently with lambda), into a second
// field; without it the pass is the paper's.
// The medium is the one the view march crosses: each cell's mu_s, inside the
// smooth surface (SurfaceDistance <= 0) only; paths cross it cell by cell.
// Voxels in the skin (near the surface, inside or out) are walked to the
// light exactly; outside ones store values continued from the inside, so a
// trilinear read just inside the surface sees no unattenuated outside light.
// With the light above the grid, a sweep layer by layer from the top makes
// the rest O(1) per voxel (LightPassSweepFromAbove); the skin voxels it meets
// are queued and walked by a dispatch of their own (LightPassWalkQueued), so
// the sweep carries none of that work, which a CPU driver would pay for every
// voxel. Otherwise each voxel walks to the light (LightPassWalkTowardsLight).
// With BRAGG_SHADOW (energy conservation, docs/design.md §7.2) each voxel
// also records the Bragg shadow it sits in: the nearest other domain on its
// path to the light and the path's length there (LightShadow).
// LightPassScatteredField writes the light scattered more than once, each
// voxel's value from the every-order solve's tally grid (§3.10).
// FORWARDED, the walks to the light go from piece to piece of the volume,
// kept between dispatches where they need another piece (§8.1).
// The mode is a specialisation constant: each pipeline holds only its own code.
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = LightPassGroupSize) in;
layout(constant_id = LightPassModeConstant) const int LIGHT_PASS_MODE = LightPassSweepFromAbove;
layout(constant_id = LightAbsorptionConstant) const bool ABSORPTION = false;
layout(constant_id = LightBraggShadowConstant) const bool BRAGG_SHADOW = false;
// Walks to the light forwarded between pieces of the volume (docs/design.md
// §8.1; LightPassMarchTowardsLight and LightPassMarchQueued): each dispatch
// walks only the layers z in work.piece and keeps a walk that needs another
// for the dispatch of that piece.
layout(constant_id = LightForwardedConstant) const bool FORWARDED = false;
// A forwarded walk's entry trace reads SurfaceDistance only at points in its
// piece, and goes on in the piece of the next (defined below).
bool surfacePointHeld(vec3 p);
#define SURFACE_POINT_HELD(p) surfacePointHeld(p)
#define PAIRED_FIELDS_CONSTANT LightPairedFieldsConstant
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"
#include "opal_voxel_walk.glsl"
#include "opal_kept_state.glsl"

#ifdef OPAL_VOLUME_ADDRESSES
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LightFieldRef { LightFieldPair value; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer AbsorptionCellRef { vec2 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LightShadowRef { LightShadow value; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer EntryVoxelRef { uint value; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer ScatteredLightRef { vec4 value; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LightFieldSingleRef { vec2 value; };
#define LIGHT_FIELD_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightField, (i), 16u)).value
#define LIGHT_ABSORPTION_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 16u)).value
#define LIGHT_FIELD_SINGLE_AT(i) LightFieldSingleRef(voxelAddress(volumeAddresses.lightField, (i), 8u)).value
#define LIGHT_ABSORPTION_SINGLE_AT(i) LightFieldSingleRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 8u)).value
// Unpaired: voxel i's value and the next one's, in one load (as view_march.comp's).
#define LIGHT_FIELD_FROM_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightField, (i), 8u)).value
#define LIGHT_ABSORPTION_FROM_AT(i) LightFieldRef(voxelAddress(volumeAddresses.lightAbsorption, (i), 8u)).value
#define ABSORPTION_CELL_AT(i) AbsorptionCellRef(voxelAddress(volumeAddresses.absorptionCells, (i), 8u)).value
#define LIGHT_SHADOW_AT(i) LightShadowRef(voxelAddress(volumeAddresses.lightShadow, (i), 12u)).value
#define ENTRY_VOXEL_AT(i) EntryVoxelRef(voxelAddress(volumeAddresses.entryVoxels, (i), 4u)).value
#define SCATTERED_LIGHT_AT(i) ScatteredLightRef(voxelAddress(volumeAddresses.scatteredLight, (i), 16u)).value
#else
layout(std430, set = 0, binding = LightFieldBinding) buffer LightField { LightFieldPair lightField[]; };
layout(std430, set = 0, binding = AbsorptionCellBinding) readonly buffer AbsorptionCells { vec2 absorptionCells[]; };
layout(std430, set = 0, binding = LightAbsorptionBinding) buffer LightAbsorption { LightFieldPair lightAbsorption[]; };
layout(std430, set = 0, binding = LightShadowBinding) buffer LightShadows { LightShadow lightShadow[]; };
layout(std430, set = 0, binding = LightEntryVoxelsBinding) buffer LightEntryVoxels { uint entryVoxels[]; };
layout(std430, set = 0, binding = ScatteredLightBinding) writeonly buffer ScatteredLight { vec4 scatteredLight[]; };
// The fields a piece may hold are read at heldIndex.
#define LIGHT_FIELD_AT(i) lightField[heldIndex(i)]
#define LIGHT_ABSORPTION_AT(i) lightAbsorption[heldIndex(i)]
// Bound fields are always paired (opal_volume_fields.glsl): these are the pair's first.
#define LIGHT_FIELD_SINGLE_AT(i) lightField[heldIndex(i)].voxel
#define LIGHT_ABSORPTION_SINGLE_AT(i) lightAbsorption[heldIndex(i)].voxel
#define LIGHT_FIELD_FROM_AT(i) lightField[heldIndex(i)]
#define LIGHT_ABSORPTION_FROM_AT(i) lightAbsorption[heldIndex(i)]
#define ABSORPTION_CELL_AT(i) absorptionCells[mediumIndex(i)]
#define LIGHT_SHADOW_AT(i) lightShadow[heldIndex(i)]
#define ENTRY_VOXEL_AT(i) entryVoxels[i]
#define SCATTERED_LIGHT_AT(i) scatteredLight[heldIndex(i)]
#endif
#include "opal_scattered_light_grid.glsl"

layout(std430, set = 0, binding = LightEntryQueuesBinding) buffer LightEntryQueues { DispatchQueue queues[]; };

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

// The light at a point: the optical depths to the light at 550 nm (x the
// scattering; y, z the coloured and grey absorption, 0 without ABSORPTION)
// and the geometry factor.
struct LightSample
{
  vec3 tau;
  float geometry;
};

// The Bragg shadow found along a path walked from a voxel towards the light
// (BRAGG_SHADOW): first the run in the voxel's own domain (phase 0), then
// cells of no other domain (1), then the first other domain's run (2), and
// nothing after it (3).
struct ShadowWalk
{
  LightShadow record;
  int own; // the voxel's domain, -1 outside domains
  int phase;
};

ShadowWalk startShadow(int own)
{
  return ShadowWalk(LightShadow(-1, 0.0, 0.0), own, 0);
}

// The walk's next `length` mm lie in `domain` (-1: none).
void followShadow(inout ShadowWalk w, int domain, float length)
{
  if (w.phase == 0 && domain >= 0 && domain == w.own)
  {
    w.record.ownLengthMm += length;
    return;
  }
  w.phase = max(w.phase, 1);
  if (w.phase == 1 && domain >= 0 && domain != w.own)
  {
    w.phase = 2;
    w.record.domain = domain;
  }
  if (w.phase == 2)
  {
    w.record.lengthMm += domain == w.record.domain ? length : 0.0;
    w.phase = domain == w.record.domain ? 2 : 3;
  }
}

// The light field and the absorption's are read and written alike, each
// through its accessors (PAIR_AT, SINGLE_AT, FROM_AT): these define, for the
// field NAME, NAMEStore and NAMERow.
// NAMEStore: a voxel's value where the field keeps it: in its own pair, and
// as the +x neighbour in the pair before it (in its own pair too at the end of
// a row), or without PAIRED_FIELDS in its own place.
// NAMERow: a row of three voxels (m - 1, m, m + 1 along x), weighted by wx:
// the pair at m - 1 holds the first two (without PAIRED_FIELDS, one load by
// address reads the value at m - 1 and the next), the value at m + 1 the third.
#define DEFINE_FIELD_ACCESS(NAME, PAIR_AT, SINGLE_AT, FROM_AT)                     \
  void NAME##Store(int index, vec2 value)                                         \
  {                                                                               \
    if (!PAIRED_FIELDS)                                                           \
    {                                                                             \
      SINGLE_AT(index) = value;                                                   \
      return;                                                                     \
    }                                                                             \
    int x = int(uint(index) % uint(P.gridDimensions.x)); /* unsigned: voxelIndex */ \
    PAIR_AT(index).voxel = value;                                                 \
    if (x > 0) PAIR_AT(index - 1).nextVoxel = value;                              \
    if (x == P.gridDimensions.x - 1) PAIR_AT(index).nextVoxel = value;            \
  }                                                                               \
  vec2 NAME##Row(int first, vec3 wx)                                              \
  {                                                                               \
    LightFieldPair left; /* not a ?:, whose mixed struct types glslang stores invalidly */ \
    vec2 right;                                                                   \
    if (PAIRED_FIELDS)                                                            \
    {                                                                             \
      left = PAIR_AT(first);                                                      \
      right = PAIR_AT(first + 2).voxel;                                           \
    }                                                                             \
    else                                                                          \
    {                                                                             \
      left = FROM_AT(first);                                                      \
      right = SINGLE_AT(first + 2);                                               \
    }                                                                             \
    return wx.x * left.voxel + wx.y * left.nextVoxel + wx.z * right;             \
  }
DEFINE_FIELD_ACCESS(light, LIGHT_FIELD_AT, LIGHT_FIELD_SINGLE_AT, LIGHT_FIELD_FROM_AT)
DEFINE_FIELD_ACCESS(absorption, LIGHT_ABSORPTION_AT, LIGHT_ABSORPTION_SINGLE_AT, LIGHT_ABSORPTION_FROM_AT)

// Stores a voxel's (optical depth, geometry factor) in the light field, its
// absorption depths likewise, its Bragg shadow with BRAGG_SHADOW.
void storeLight(int index, LightSample light, ShadowWalk shadow)
{
  if (BRAGG_SHADOW) LIGHT_SHADOW_AT(index) = shadow.record;
  lightStore(index, vec2(light.tau.x, light.geometry));
  if (ABSORPTION) absorptionStore(index, light.tau.yz);
}

// A voxel's extinction coefficients at 550 nm: (mu_s, coloured mu_a, grey mu_a).
vec3 mediumOf(VoxelCell voxel, int index)
{
  return vec3(voxel.scattering, ABSORPTION ? ABSORPTION_CELL_AT(index) : vec2(0.0));
}

vec3 mediumAt(int index)
{
  return mediumOf(VOXEL_CELL_AT(index), index);
}

vec3 mediumIn(ivec3 cell)
{
  return insideGrid(cell) ? mediumAt(voxelIndex(cell)) : vec3(0.0);
}

// What a walk needs of a cell, from one read of its VoxelCell: its
// coefficients (mediumAt) and its domain (-1 outside domains and the grid).
struct CellContents
{
  vec3 medium;
  int domain;
};

CellContents contentsOf(ivec3 cell)
{
  if (!insideGrid(cell)) return CellContents(vec3(0.0), -1);
  int index = voxelIndex(cell);
  VoxelCell voxel = VOXEL_CELL_AT(index);
  return CellContents(mediumOf(voxel, index), voxel.domainId);
}

// The skin: outside voxel centres nearer the surface than a cell's diagonal
// are corners of trilinear reads at points inside, so they need values.
float skinDepth()
{
  return length(P.gridSpacing);
}

// Whether a forwarded walk's piece holds layer z (those beyond the grid in its
// first or last piece); the layer of the last one asked about, where a kept
// walk goes on. Unforwarded every layer is held.
int neededLayer;
bool layerHeld(int z)
{
  if (!FORWARDED) return true;
  neededLayer = clamp(z, 0, P.gridDimensions.z - 1);
  return neededLayer >= work.piece.x && neededLayer < work.piece.y;
}

bool surfacePointHeld(vec3 p)
{
  return layerHeld(voxelOf(p).z);
}

// Whether a forwarded walk inside, going along z by stepZ, may read the cell
// of layer z: its piece's, or one of the TraceStepLayers + 1 layers before
// the piece on the side it comes from, where a trace's bisection may put the
// walk's start (the cells' halo there, docs/design.md §8.1). A walk so never
// goes back to a piece it left: it moves one way in z from its start.
bool walkLayerHeld(int z, int stepZ)
{
  int behind = TraceStepLayers + 1;
  bool inHalo = stepZ > 0 ? z < work.piece.x && z >= work.piece.x - behind
                          : stepZ < 0 && z >= work.piece.y && z < work.piece.y + behind;
  return !FORWARDED || inHalo || layerHeld(z);
}

// The light's trace of the surface entry: steps of at least half the least
// spacing, none passing more than TraceStepLayers layers z (forwarded, the
// bisection after them then reads within the piece's halo; unforwarded the
// same, so that both find the same surface), pausing where forwarded.
TraceRule lightTrace()
{
  return TraceRule(true, 0.5 * P.smallestSpacing, float(TraceStepLayers), FORWARDED);
}

// walkInside's loop, kept between a forwarded walk's dispatches: the cell
// walk, the distance walked and the distance known to be inside, its steps.
struct InsideWalk
{
  VoxelWalk walk;
  float s;
  float safe;
  int steps;
};

InsideWalk startInside(vec3 p, vec3 direction, float t)
{
  return InsideWalk(startWalk(p + t * direction, direction), 0.0, 0.0, 0);
}

// Walks the path from p + t direction cell by cell while it stays inside the
// smooth surface, adding each cell's coefficients times its length there to tau;
// `exit`: where the path leaves the surface (bisected), or tEnd. The surface
// is tested only beyond the distance known to be safe, as sphere tracing
// does (a distance field changes at most as fast as one moves). False where
// a forwarded walk needs a cell its piece does not hold: it goes on from
// `w` in the piece that does, as if never interrupted.
bool walkInside(inout InsideWalk w, vec3 p, vec3 direction, float t, float tEnd, inout vec3 tau,
  inout ShadowWalk shadow, out float exit)
{
  exit = tEnd;
  vec3 origin = p + t * direction;
  float span = tEnd - t;
  // The cell the path leaves the surface in, bisected after the loop (lavapipe
  // would run the bisection under a mask in every cell).
  bool left = false;
  float sLeft = 0.0;
  CellContents last;
  for (; w.steps < 65536 && w.s < span; ++w.steps)
  {
    if (!walkLayerHeld(w.walk.cell.z, w.walk.stepDir.z)) return false;
    float sNext = min(cellExit(w.walk), span);
    CellContents contents = contentsOf(w.walk.cell);
    vec3 medium = contents.medium;
    if (sNext > w.safe)
    {
      float d = surfaceDistance(origin + sNext * direction);
      if (d > 0.0)
      {
        left = true;
        sLeft = sNext;
        last = contents;
        break;
      }
      w.safe = sNext - 0.9 * d;
    }
    tau += medium * (sNext - w.s);
    if (BRAGG_SHADOW) followShadow(shadow, contents.domain, sNext - w.s);
    w.s = sNext;
    stepWalk(w.walk);
  }
  if (!left) return true;
  float sOut = bisectSurface(origin, direction, sLeft, w.s);
  tau += last.medium * max(sOut - w.s, 0.0);
  if (BRAGG_SHADOW) followShadow(shadow, last.domain, max(sOut - w.s, 0.0));
  exit = t + sOut;
  return true;
}

// A voxel's walk to the light (lightWalkOn), in the order of its phases.
const int LightWalkUnstarted = -1; // a forwarded walk whose voxel's piece comes later
const int LightWalkStretches = 0; // the stretches inside the opal, to the light
const int LightWalkContinued = 1; // no stretch: the value continued from the inside
const int LightWalkMedium = 2;    // that value's coefficients, read at `point`
const int LightWalkNearestInside = 3; // or that value's point just inside, `point`, read
const int LightWalkFromInside = 4; // and walked from to the light
const int LightWalkDone = 5;

// All a walk to the light carries from step to step (all a forwarded walk
// keeps, keepLightWalk): its phase, the stretch loop's t, the light's entry
// so far and the stretch, whether it traces or walks, the entry trace, the
// walk inside, the optical depths, the geometry factor, the Bragg shadow, and
// the continued value's point and length back.
struct LightWalk
{
  int phase;
  float t;
  float lightEntry;
  int stretch;
  bool tracing;
  SurfaceTrace trace;
  InsideWalk inside;
  vec3 tau;
  float geometry;
  ShadowWalk shadow;
  vec3 point;
  float back;
};

// The way from the point just inside (`point`) to the light: one expression
// where its walk starts, walks and is taken up (keepLightWalk sets its steps
// again from it, bit for bit).
vec3 fromInsideToLight(LightWalk w)
{
  return normalize(P.light - w.point);
}

// The exact light at p (eq. 6, 7): the path to the light
// crossed cell by cell through every stretch inside the opal; the light
// enters where the stretch nearest the light leaves it (L_in). An outside
// p behind the opal thus gets the light through it, one beside it the
// continuation (continueFromInside). False where forwarded and paused.
bool walkStretches(inout LightWalk w, vec3 p, vec3 direction, float tEnd)
{
  for (; w.stretch < 64 && w.t < tEnd; ++w.stretch)
  {
    if (w.tracing)
    {
      if (!traceSurfaceOn(w.trace, p, direction, tEnd, lightTrace(), 1e30)) return false;
      w.t = w.trace.t;
      if (w.t < 0.0) break;
      w.inside = startInside(p, direction, w.t);
      w.tracing = false;
    }
    float exit;
    if (!walkInside(w.inside, p, direction, w.t, tEnd, w.tau, w.shadow, exit)) return false;
    w.lightEntry = exit;
    // Where the light enters: forwarded, its geometry as each walk ends, in
    // the piece that holds the point; unforwarded once, at the end (lightWalkOn).
    if (FORWARDED) w.geometry = entryGeometry(p, p + exit * direction, direction);
    if (BRAGG_SHADOW) followShadow(w.shadow, -1, 0.0); // outside between stretches
    w.t = w.lightEntry + 0.5 * P.smallestSpacing;
    w.trace = surfaceTrace(w.t);
    w.tracing = true;
  }
  return true;
}

// The nearest point just inside (`point`), read where its piece holds it (on
// a grid much finer in z it may lie beyond p's halo): beside the grid's
// faces the field's continuation has no nearest point to offer; else its
// walk to the light starts.
void startFromInside(inout LightWalk w, vec3 p)
{
  if (!insideGrid(voxelOf(w.point)) || surfaceDistance(w.point) > 0.0)
  {
    float r = distance(P.light, p);
    w.geometry = P.apexDistanceSquared / (r * r);
    w.phase = LightWalkDone;
    return;
  }
  w.inside = startInside(w.point, fromInsideToLight(w), 0.0);
  w.phase = LightWalkFromInside;
}

// An outside voxel whose path to the light misses the opal: values
// continued from the inside, so that reads between it and inside voxels
// stay close to the inside's. Where the surface below it faces the light,
// linearly across that surface (d / cos_L back along the path): the optical
// depth negative in proportion to the distance, the Fresnel transmission at
// cos_L (its coefficients read next, LightWalkMedium). Beside the shadow
// line (cos_L small), the light of the nearest point just inside, walked to
// the light next (LightWalkNearestInside; unattenuated light there would
// brighten the terminator). From the voxel's own distance and the field's
// slope along the path: no search, which a CPU driver would pay for every
// skin voxel.
void continueFromInside(inout LightWalk w, vec3 p, vec3 direction, float d)
{
  // cos_L = dot(normal, direction): SurfaceDistance's derivative along the path.
  float cosL = (d - surfaceDistance(p - P.smallestSpacing * direction)) / P.smallestSpacing;
  if (cosL > 0.25)
  {
    w.back = d / cosL;
    w.point = p - (w.back + 0.5 * P.smallestSpacing) * direction;
    float falloff = P.lightFalloffAtEntry != 0 ? distance(P.light, p - w.back * direction) : distance(P.light, p);
    float transmission = 1.0 - fresnelReflectance(cosL, P.refractiveIndex);
    w.geometry = transmission * P.apexDistanceSquared / (falloff * falloff);
    w.phase = LightWalkMedium;
    return;
  }
  w.point = p - (d + 0.01 * P.smallestSpacing) * surfaceNormal(p);
  w.phase = LightWalkNearestInside;
  // Unforwarded at once (a phase block of its own cost lavapipe, which runs
  // it under a mask for every lane, 4% of a side light's pass).
  if (!FORWARDED) startFromInside(w, p);
}

// Takes the walk to the light from voxel `index` at p (SurfaceDistance d,
// where it started in this dispatch) on through its phases until it is done
// (true), or, forwarded, needs a layer its piece does not hold (false:
// neededLayer).
bool lightWalkOn(inout LightWalk w, int index, vec3 p, vec3 direction, float tEnd, float d)
{
  if (w.phase == LightWalkStretches)
  {
    if (!walkStretches(w, p, direction, tEnd)) return false;
    w.phase = w.lightEntry >= 0.0 ? LightWalkDone : LightWalkContinued;
  }
  if (w.phase == LightWalkContinued)
  {
    if (!layerHeld(voxelOf(p).z)) return false;
    // Forwarded, read again in p's piece: a walk taken up has not read it.
    // (Unforwarded the read is not repeated: lavapipe would load it for every lane.)
    continueFromInside(w, p, direction, FORWARDED ? voxelSurfaceDistance(index) : d);
  }
  if (w.phase == LightWalkMedium)
  {
    ivec3 cell = voxelOf(w.point);
    if (!layerHeld(cell.z)) return false;
    w.tau = -mediumIn(cell) * w.back;
    w.phase = LightWalkDone;
  }
  // Unforwarded, one entryGeometry for either way the light enters (a normal:
  // six SurfaceDistance reads), at the end: lavapipe would run two calls under a mask.
  bool entered = w.lightEntry >= 0.0;
  vec3 entry = p + w.lightEntry * direction, along = direction;
  if (FORWARDED && w.phase == LightWalkNearestInside)
  {
    if (!layerHeld(voxelOf(w.point).z)) return false;
    startFromInside(w, p);
  }
  if (w.phase == LightWalkFromInside)
  {
    vec3 towardLight = fromInsideToLight(w);
    float tEndInside = min(gridBoxHits(w.point, towardLight).y, distance(P.light, w.point));
    float exit;
    if (!walkInside(w.inside, w.point, towardLight, 0.0, tEndInside, w.tau, w.shadow, exit)) return false;
    entered = true;
    entry = w.point + exit * towardLight;
    along = towardLight;
    if (FORWARDED) w.geometry = entryGeometry(p, entry, along);
    w.phase = LightWalkDone;
  }
  if (!FORWARDED && entered) w.geometry = entryGeometry(p, entry, along);
  return true;
}

// A voxel's walk to the light as it starts: inside, walking from p; outside,
// tracing its entry.
LightWalk startLightWalk(int index, vec3 p, vec3 direction, float d)
{
  LightWalk w;
  w.phase = LightWalkStretches;
  w.t = 0.0;
  w.lightEntry = -1.0;
  w.stretch = 0;
  w.tracing = !(d <= 0.0);
  w.trace = surfaceTrace(0.0);
  if (!w.tracing) w.inside = startInside(p, direction, 0.0);
  w.tau = vec3(0.0);
  w.geometry = 0.0;
  w.shadow = startShadow(BRAGG_SHADOW ? VOXEL_CELL_AT(index).domainId : -1);
  w.point = p;
  w.back = 0.0;
  return w;
}

// Saves (`saving`) or restores the walk of invocation `slot` of a forwarded
// light pass (from p along `direction`): its voxel, then everything its
// steps read again, bit for bit (LightStateWords with the layer word); its
// voxel and phase alone where it has not started.
void keepLightWalk(int slot, bool saving, inout int voxel, inout LightWalk w, vec3 direction)
{
  beginKeeping(slot, LightStateWords, saving);
  keepInt(voxel);
  keepInt(w.phase);
  if (w.phase == LightWalkUnstarted) return; // its start sets the rest
  keepFloat(w.t);
  keepFloat(w.lightEntry);
  keepInt(w.stretch);
  keepBool(w.tracing);
  keepTrace(w.trace);
  keepFloat(w.inside.s);
  keepFloat(w.inside.safe);
  keepInt(w.inside.steps);
  keepVec3(w.tau);
  keepFloat(w.geometry);
  keepShadow(w.shadow.record);
  keepInt(w.shadow.own);
  keepInt(w.shadow.phase);
  keepVec3(w.point);
  keepFloat(w.back);
  // Its walk inside goes from p to the light, or from the point just inside (startFromInside).
  keepVoxelWalk(w.inside.walk, w.phase == LightWalkFromInside ? fromInsideToLight(w) : direction);
}

// Queues a voxel of layer y for LightPassMarchQueued (an append list and the
// workgroups of its indirect dispatch). The list holds one layer: the layer's
// march reads it before the next layer's sweep writes it again (a barrier
// follows every dispatch, docs/design.md §3.7).
void queueVoxel(int index, int y)
{
  uint slot = atomicAdd(queues[y].count, 1u);
  ENTRY_VOXEL_AT(int(slot)) = uint(index);
  if (slot % uint(LightPassGroupSize) == 0u)
  {
    uvec2 grid = dispatchGrid(slot / uint(LightPassGroupSize) + 1u);
    atomicMax(queues[y].groupsX, grid.x);
    atomicMax(queues[y].groupsY, grid.y);
    if (slot == 0u) queues[y].groupsZ = 1u; // the queue starts all zero: a dispatch of none
  }
}

// The Bragg shadow of a voxel in domain `own` whose path to the light reaches,
// `length` mm on, a voxel in domain `upDomain` whose shadow is `up`: within
// one domain the run grows; leaving a domain, that domain casts the shadow.
LightShadow shadowFromAbove(LightShadow up, int upDomain, int own, float length)
{
  float ownLength = own >= 0 ? length : 0.0;
  if (upDomain == own)
  {
    return LightShadow(up.domain, up.lengthMm, up.ownLengthMm + ownLength);
  }
  return upDomain >= 0 ? LightShadow(upDomain, up.ownLengthMm, ownLength) : LightShadow(up.domain, up.lengthMm, ownLength);
}

// The biquadratic Lagrange weights of the nodes -1, 0, +1 at offset u
// (|u| <= 1/2) from the middle one: exact for a quadratic.
vec3 quadraticWeights(float u)
{
  return vec3(0.5 * u * (u - 1.0), 1.0 - u * u, 0.5 * u * (u + 1.0));
}

// The largest SurfaceDistance of a row of three.
float rowDistance(int first)
{
  vec2 left = surfaceDistancePair(first);
  return max(max(left.x, left.y), voxelSurfaceDistance(first + 2));
}

// LightPassSweepFromAbove: the path from p to the light crosses the plane of
// the layer above at q; the light there is interpolated from that layer's
// 3 x 3 voxels around q, biquadratically, and the short segment p-q added.
// O(1) per voxel. Bilinear reads, chained layer after layer, smoothed the
// optical depth sideways like a diffusion (a path drifting a fraction f of a
// cell per layer spreads by f (1 - f) h^2 per layer): where the depth curves
// sideways, under the steep rim of a dome lit from above, that made it too
// small, the rim too bright by up to 1% at 0.2 mm (docs/design.md §3.3).
// Skin voxels (outside, or with an outside voxel among the 3 x 3, or in the
// top layer, or beside the grid's sides) are queued for the exact walk
// instead: interpolating over outside values, or only over the inside ones,
// is what darkened the rim on steep sides.
void sweepFromLayerAbove(int index, ivec3 c, vec3 p, vec3 direction)
{
  float step = P.gridSpacing.y / direction.y;
  vec3 q = p + step * direction;
  vec2 g = (q.xz - P.gridOrigin.xz) / P.gridSpacing.xz;
  ivec2 m = ivec2(floor(g + 0.5));
  int above = c.y + 1;
  bool skin = above >= P.gridDimensions.y || voxelSurfaceDistance(index) > 0.0 || any(lessThan(m, ivec2(1))) ||
    any(greaterThan(m, P.gridDimensions.xz - 2));
  int first = skin ? 0 : voxelIndex(ivec3(m.x - 1, above, m.y - 1));
  int rowStride = P.gridDimensions.x * P.gridDimensions.y;
  skin = skin || max(max(rowDistance(first), rowDistance(first + rowStride)), rowDistance(first + 2 * rowStride)) > 0.0;
  if (skin)
  {
    queueVoxel(index, c.y);
    return;
  }
  vec3 wx = quadraticWeights(g.x - float(m.x)), wz = quadraticWeights(g.y - float(m.y));
  vec2 lightQ = wz.x * lightRow(first, wx) + wz.y * lightRow(first + rowStride, wx) + wz.z * lightRow(first + 2 * rowStride, wx);
  vec2 absorptionQ = vec2(0.0);
  if (ABSORPTION)
  {
    absorptionQ = wz.x * absorptionRow(first, wx) + wz.y * absorptionRow(first + rowStride, wx) +
      wz.z * absorptionRow(first + 2 * rowStride, wx);
  }
  // Two half-segments, each with the coefficients of the voxel it lies in.
  vec3 segment = 0.5 * step * (mediumAt(index) + mediumIn(voxelOf(p + 0.75 * step * direction)));
  // Along one light path the Fresnel factor is constant: rescale the fall-off from q to p.
  float rq = distance(P.light, q), rp = distance(P.light, p);
  ShadowWalk shadow = startShadow(-1);
  if (BRAGG_SHADOW)
  {
    // The nearest voxel to q carries its shadow on (domain ids do not interpolate).
    int nearest = voxelIndex(ivec3(m.x, above, m.y));
    shadow.record = shadowFromAbove(LIGHT_SHADOW_AT(nearest), VOXEL_CELL_AT(nearest).domainId, VOXEL_CELL_AT(index).domainId, step);
  }
  storeLight(index, LightSample(vec3(max(lightQ.x, 0.0), max(absorptionQ, vec2(0.0))) + segment,
    P.lightFalloffAtEntry != 0 ? lightQ.y : lightQ.y * (rq * rq) / (rp * rp)), shadow);
}

// The voxel this invocation (its walk's state in slot `slot`) lights, or -1
// (an index's bits unsigned beyond 2^31: voxelIndex).
// A queued walk's is its queue's entry; in a light pass shared by processes
// (docs/design.md §8.1), where a later round's dispatch takes up `count`
// walks of a share's queue (this device's queue may be another share's),
// the voxel kept with its walk (read before its layer word says whether it
// goes on here: nothing is read at it before that).
int voxelOfInvocation(int slot)
{
  int nx = P.gridDimensions.x, ny = P.gridDimensions.y;
  int local = passItem(LightPassGroupSize);
  if (LIGHT_PASS_MODE == LightPassMarchTowardsLight || LIGHT_PASS_MODE == LightPassScatteredField)
  {
    return local < work.count ? int(work.first + uint(local)) : -1;
  }
  if (LIGHT_PASS_MODE == LightPassMarchQueued && work.count > 0)
  {
    return local < work.count ? int(keptStates[slot * LightStateWords + 1]) : -1;
  }
  if (LIGHT_PASS_MODE == LightPassMarchQueued)
  {
    return local < int(queues[work.layer].count) ? int(ENTRY_VOXEL_AT(local)) : -1;
  }
  return local < nx * work.count ? local % nx + nx * (work.layer + ny * (int(work.first) + local / nx)) : -1;
}

// A forwarded walk to the light in this dispatch: in the first, a voxel of
// another piece's kept untouched for it (false); in a later one, its walk
// taken up again where this piece holds the layer it goes on in (false
// where done or elsewhere: one word read); `started` once begun.
bool takeUpWalk(int slot, int index, ivec3 c, vec3 direction, out LightWalk w, out bool started)
{
  started = false;
  int voxel = index;
  if (work.resumed == 0)
  {
    if (layerHeld(c.z)) return true;
    // Not started: its voxel's own reads wait for its piece.
    keepLayer(slot, LightStateWords, uint(neededLayer));
    w.phase = LightWalkUnstarted;
    keepLightWalk(slot, true, voxel, w, direction);
    return false;
  }
  uint layer = keptLayer(slot, LightStateWords);
  if (!keptGoesOn(layer) || !layerHeld(int(layer))) return false;
  keepLightWalk(slot, false, voxel, w, direction);
  started = w.phase != LightWalkUnstarted;
  return true;
}

void main()
{
  int slot = work.slotFirst + passItem(LightPassGroupSize);
  int index = voxelOfInvocation(slot);
  if (index == -1) return;
  ivec3 c = voxelOfIndex(index);
  if (LIGHT_PASS_MODE == LightPassScatteredField)
  {
    // Zero where nothing scatters, as the march reads it only where something does.
    SCATTERED_LIGHT_AT(index) = VOXEL_CELL_AT(index).scattering > 0.0 ? scatteredLightAt(c) : vec4(0.0);
    return;
  }
  vec3 p = voxelCentre(c);
  vec3 toLight = P.light - p;
  float distanceToLight = length(toLight);
  vec3 direction = toLight / distanceToLight;
  LightWalk w;
  bool started = false;
  bool last = FORWARDED && work.last != 0;
  if (FORWARDED && !takeUpWalk(slot, index, c, direction, w, started))
  {
    countUnfinished(slot, LightStateWords, last);
    return;
  }
  float d = 0.0;
  if (!started)
  {
    // A voxel centre: its own SurfaceDistance, no interpolation needed.
    d = voxelSurfaceDistance(index);
    if (LIGHT_PASS_MODE != LightPassMarchQueued && d > skinDepth())
    {
      // Outside beyond the skin: nothing inside reads it; unattenuated light.
      storeLight(index, LightSample(vec3(0.0), P.apexDistanceSquared / (distanceToLight * distanceToLight)),
        startShadow(-1));
      if (FORWARDED) keepLayer(slot, LightStateWords, KeptDone);
      return;
    }
    if (LIGHT_PASS_MODE == LightPassSweepFromAbove)
    {
      sweepFromLayerAbove(index, c, p, direction);
      return;
    }
    w = startLightWalk(index, p, direction, d);
  }
  bool done = lightWalkOn(w, index, p, direction, min(gridBoxHits(p, direction).y, distanceToLight), d);
  // Forwarded, a finished walk is stored in the piece that holds its voxel
  // (between ranks, the rank that holds it), which takes it up again.
  // Unforwarded every walk finishes here: the constant folds the keeping away.
  if (!done || (FORWARDED && !layerHeld(c.z)))
  {
    keepLayer(slot, LightStateWords, uint(neededLayer));
    keepLightWalk(slot, true, index, w, direction);
    countUnfinished(slot, LightStateWords, last);
    return;
  }
  storeLight(index, LightSample(w.tau, w.geometry), w.shadow);
  if (FORWARDED) keepLayer(slot, LightStateWords, KeptDone);
}
