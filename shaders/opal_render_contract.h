// The host-shader contract of the render (docs/design.md §3.8): binding
// numbers, the parameter block, the wavelength-bin record, one push-constant
// struct per pass and the light pass's modes. The GLSL passes and the C++ of
// OpalGpu include this one file, so the two sides cannot drift apart;
// TestOpalShaderContract checks that both lay every field out at the same
// offset (glslang's reflection against offsetof).
//
// Layout rules kept by hand: every vec3 is followed by a 4-byte scalar (std140
// and std430 align a vec3 to 16 bytes; alignas(16) does so in C++), ivec2 sits
// at a multiple of 8, and each struct is a multiple of 16 bytes.
// Lengths are in mm, wavelengths in nm, all positions in the model's frame.
#ifndef OPAL_RENDER_CONTRACT_H
#define OPAL_RENDER_CONTRACT_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace opal::gpu
{
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using uvec2 = glm::uvec2;
#define OPAL_CONSTANT constexpr
#define OPAL_ALIGNED alignas(16)
#else
#define OPAL_CONSTANT const
#define OPAL_ALIGNED
#endif

// Descriptor bindings of the one set every pass shares (each pass declares
// the ones it uses).
OPAL_CONSTANT int ParametersBinding = 0;       // uniform RenderParameterBlock
OPAL_CONSTANT int WavelengthTableBinding = 1;  // WavelengthBinRecord per wavelength
OPAL_CONSTANT int VoxelCellBinding = 2;        // VoxelCell per voxel: ScatteringCoefficient and DomainId
OPAL_CONSTANT int HighlightPixelsBinding = 3;  // uint per pixel: the pixels queued for the highlight
// Binding 4, 5 and 17 hold pairs (a voxel's value and its +x neighbour's);
// fields read by address hold one value per voxel (PairedFields below).
OPAL_CONSTANT int SurfaceDistanceBinding = 4;  // vec2 per voxel: its SurfaceDistance (mm, negative inside) and its +x neighbour's
OPAL_CONSTANT int LightFieldBinding = 5;       // LightFieldPair per voxel
OPAL_CONSTANT int DomainTableBinding = 6;      // DomainRecord per domain
OPAL_CONSTANT int PixelColourBinding = 7;      // PixelColour per pixel
OPAL_CONSTANT int PixelBraggBinding = 8;       // PixelBragg per pixel
OPAL_CONSTANT int PixelSpectrumBinding = 9;    // wavelengthCount floats per pixel
OPAL_CONSTANT int PixelRadianceBinding = 10;   // 3 floats per pixel: linear sRGB
OPAL_CONSTANT int PixelRGB8Binding = 11;       // uint per pixel: 8-bit sRGB, R in the low byte
OPAL_CONSTANT int LightEntryQueuesBinding = 12; // DispatchQueue per layer of the grid
OPAL_CONSTANT int LightEntryVoxelsBinding = 13; // uint per voxel of a layer: the layer being swept's queued voxels
OPAL_CONSTANT int PixelMirrorBinding = 14;     // PixelMirror per pixel
OPAL_CONSTANT int HighlightQueueBinding = 15;  // one DispatchQueue, its count: the pixels queued for the highlight
// Absorption (docs/design.md §3.9), read only by the passes specialised on it
// (ABSORPTION); without absorption both hold a placeholder.
OPAL_CONSTANT int AbsorptionCellBinding = 16;   // vec2 per voxel: mu_a at 550 nm, coloured and grey (1/mm)
OPAL_CONSTANT int LightAbsorptionBinding = 17;  // LightFieldPair per voxel: absorption depths to the light, coloured and grey
// Energy conservation on the light path (docs/design.md §7.2), written by the
// light pass and read by the march specialised on it; else a placeholder.
OPAL_CONSTANT int LightShadowBinding = 18;      // LightShadow per voxel
// Per domain, what it passes of the light per bin and the light path's
// length from which that holds (a row of vec4s, see ShadowTableGroupSize),
// written each frame by the Bragg shadow table pass and read by the march,
// both specialised on energy conservation; else a placeholder.
OPAL_CONSTANT int ShadowTableBinding = 19;      // a row of SHADOW_TABLE_ROW_VEC4S vec4s per domain
// The light scattered at least once (every order, docs/design.md §3.10): per
// voxel a vec4, its mean radiance over s at the four nodes spanning the
// table's s, written from the tally grid by the light pass's
// LightPassScatteredField; a placeholder without ScatteringOrders all.
OPAL_CONSTANT int ScatteredLightBinding = 20;
// Where a per-voxel field outgrows one storage buffer (maxStorageBufferRange),
// the passes compiled with OPAL_VOLUME_ADDRESSES read every per-voxel field
// through its device address (docs/design.md §3.7); else a placeholder.
OPAL_CONSTANT int VolumeAddressesBinding = 21; // one VolumeAddresses
// The pixels whose footprint an edge crosses (docs/design.md §3.4): queued by
// the march's edge select, marched again with PixelSamples^2 sub-rays.
OPAL_CONSTANT int EdgeQueueBinding = 22;        // two DispatchQueues, their counts: the select's, the second stage's
OPAL_CONSTANT int EdgePixelsBinding = 23;       // two uints per pixel: the queued pixels, then the second stage's
OPAL_CONSTANT int PixelSumsBinding = 24;        // PixelSum per queued pixel: its sub-rays' sums so far
// The every-order solve's coarse tally grid (up to 65^3 nodes), read by
// LightPassScatteredField; a placeholder without ScatteringOrders all.
OPAL_CONSTANT int ScatteredLightGridBinding = 25; // ScatteredLightNode per node
// The view march's rays between the dispatches of a forwarded march (§8.1):
// RAY_STATE_WORDS uints per invocation of a dispatch; a placeholder otherwise.
OPAL_CONSTANT int RayStatesBinding = 26;
// A forwarded pass's count of the states its last dispatch left unfinished
// (§8.1): one uint, which the host requires to stay 0; a placeholder otherwise.
OPAL_CONSTANT int ForwardedLeftBinding = 27;
// SurfaceDistance as the highlight pass reads it (docs/design.md §3.4): the
// grid's cells in tiles of SurfaceTileCells^3, each held exact or standing as
// one bound (core/render/OpalSurfaceTiles.h), so that every process holds it
// whole while the field is held by piece.
OPAL_CONSTANT int SurfaceTileBinding = 28;       // SurfaceTile per tile, x fastest
OPAL_CONSTANT int SurfaceTileValuesBinding = 29; // (SurfaceTileCells + 1)^3 floats per tile held, x fastest
OPAL_CONSTANT int BindingCount = 30;
OPAL_CONSTANT int SurfaceTileCells = 8;

// The highlight pass's modes, one pipeline each (specialisation constant 0).
OPAL_CONSTANT int HighlightSelect = 0; // every pixel: queue those near the light's mirror image
OPAL_CONSTANT int HighlightShade = 1;  // the queued pixels: supersample the highlight
OPAL_CONSTANT int HighlightGroupSize = 64;
// The colour pass's workgroup (one pixel each) and the march's (a square of pixels).
OPAL_CONSTANT int ColourGroupSize = 64;
OPAL_CONSTANT int MarchGroupSide = 8;

// Every setting of a frame. A uniform block: read-only and never aliased by
// the storage buffers, so compilers keep it in registers.
struct OPAL_ALIGNED RenderParameterBlock
{
  OPAL_ALIGNED ivec3 gridDimensions;  // voxels in x, y, z
  int wavelengthCount;                // entries of the wavelength table
  OPAL_ALIGNED vec3 gridOrigin;       // centre of voxel (0, 0, 0)
  float smallestSpacing;              // the smallest of the three spacings
  OPAL_ALIGNED vec3 gridSpacing;
  float marchStep;                    // longest scattering sub-step of the view march
  OPAL_ALIGNED vec3 eye;
  float tanHalfViewAngle;             // tan of half the vertical view angle
  OPAL_ALIGNED vec3 forward;          // unit view direction
  int writeSpectrum;                  // 1: fill the Spectrum image
  OPAL_ALIGNED vec3 right;            // unit image x
  int imageWidth;                     // pixels of the whole image
  OPAL_ALIGNED vec3 up;               // unit image y
  int imageHeight;
  OPAL_ALIGNED vec3 light;            // the light's centre
  float lightRadius;
  OPAL_ALIGNED vec3 background;       // linear sRGB of the background
  float exposure;                     // scale of the radiance before the tone map
  ivec2 rectOrigin;                   // the rendered sub-rectangle of the image: first pixel
  ivec2 rectSize;                     // and its width and height
  float refractiveIndex;              // mu of the opal
  float braggBandwidth;               // relative full width of the Bragg band B
  float diffractionGain;              // G (paper §5)
  float mosaicSpread;                 // radians; 0: off
  float apexDistanceSquared;          // light-apex distance^2: irradiance 1 at the apex
  float lightRadiance;                // the light disc's radiance for irradiance 1 at the apex
  int lightFalloffAtEntry;            // 1: the paper's eq. 6, 1/r^2 stops at L_in
  int specularSamples;                // sub-rays per pixel axis for the highlight
  int pixelSamples;                   // sub-rays per pixel axis where an edge crosses a pixel (1: none)
  int domainCount;
  int braggOrders;                    // orders k = 1..braggOrders
  float absorptionExponent;           // p of the coloured absorption, mu_a(lambda) = mu_a(550) (550/lambda)^p
  // The coupled-wave model (docs/design.md §7.2), read only by the march specialised on it:
  float meanIndex;                    // n_bar = sqrt(f n_s^2 + (1 - f) n_m^2)
  float permittivityContrast;         // f (n_s^2 - n_m^2): eps_G = this x 3 j1(x)/x
  float coherentLayers;               // CoherentLayers, the most layers N
  int latticeFamilies;                // 1: (111) only; 13: the FCC families
  int maxGroupsX;                     // the device's maxComputeWorkGroupCount[0] as the session plans with it
  // The every-order field's tally grid (docs/design.md §3.10): its nodes per
  // axis, and voxels per cell (node i of an axis sits at voxel i x stride).
  OPAL_ALIGNED ivec3 scatteredLightNodes;
  int scatteredLightStride;
  // The first voxel that the light fields and the every-order field hold,
  // bound (a piece of a march shared by processes, §8.1): an index less
  // it. 0 where they are addressed, whose addresses are shifted instead.
  int heldFirstVoxel;
  // The same for the medium (cells, absorption cells, SurfaceDistance), which holds a
  // piece where it was uploaded by piece (a wider halo than the light fields').
  int mediumFirstVoxel;
};

// One wavelength bin (core/colour/OpalSpectralSampling.h): its centre and width,
// the Rayleigh scale (550/lambda)^4, the normalised D65 power and the
// bin-averaged CIE 1931 colour-matching functions.
struct OPAL_ALIGNED WavelengthBinRecord
{
  float lambda;
  float width;
  float rayleighScale;
  float illuminant;
  OPAL_ALIGNED vec3 colourMatching;   // x-bar, y-bar, z-bar
};

// A voxel's piecewise-constant fields (the skin filled, docs/design.md §3.3),
// read together: the view march's walk takes one load per voxel, not two.
struct VoxelCell
{
  float scattering; // ScatteringCoefficient, 1/mm at 550 nm
  int domainId;     // -1 or an index into the domain table
};

// A tile of SurfaceDistance (SurfaceTileBinding): its values' slot in
// SurfaceTileValuesBinding, or -1 where `bound` stands for the whole tile
// (the least |SurfaceDistance| read in it, with its sign).
struct SurfaceTile
{
  int slot;
  float bound;
};

// The light field (docs/design.md §3.3) of a voxel and of its +x neighbour
// (the last voxel of a row repeats itself), each as (optical depth to the
// light at 550 nm, Fresnel transmission x fall-off): a trilinear read takes
// four loads instead of sixteen. The absorption field (§3.9) has the same
// layout, each as (coloured, grey) absorption depth to the light at 550 nm.
struct OPAL_ALIGNED LightFieldPair
{
  vec2 voxel;
  vec2 nextVoxel;
};

// The Bragg shadow a voxel sits in (docs/design.md §7.2): the nearest domain
// other than its own that the straight path to the light crosses (-1: none)
// and the path's length in it; and the path's length in the voxel's own
// domain before it (0 outside domains), which the sweep carries on.
struct LightShadow
{
  int domain;
  float lengthMm;
  float ownLengthMm;
};

// A node of the every-order field's coarse tally grid (docs/design.md §3.10):
// the solve's tallies at the four spectral nodes, each over 4 pi s, and the
// inside volume the node's trilinear weights give it. A voxel's value is the
// kernel estimate of the eight nodes around its centre, sum(w tally) / sum(w volume)
// (OpalScatteredLight's meanRadiance).
struct OPAL_ALIGNED ScatteredLightNode
{
  vec4 tally;
  float volume;
};

// One diffraction domain: the (111) lattice-plane normal (y >= 0), the
// plane spacing d (nm, eq. 3), the lattice orientation, crystal frame ->
// model frame, as a unit quaternion stored (x, y, z, w) (docs/design.md §7.2),
// and the mean of its voxels' centres (where the Bragg shadow table takes the
// direction to the light).
struct OPAL_ALIGNED DomainRecord
{
  OPAL_ALIGNED vec3 latticeNormal;
  float planeSpacing;
  OPAL_ALIGNED vec4 orientation;
  OPAL_ALIGNED vec3 centre;
  float unused; // std430 padding after the vec3
};

// The Bragg shadow table (docs/design.md §7.2): domain i's row is vec4s
// [i r, (i + 1) r), r = SHADOW_TABLE_ROW_VEC4S(wavelengthCount); of its floats,
// [0, wavelengthCount) are what the domain passes of the light per bin, for a
// path long enough to cross CoherentLayers layers of every family that
// reflects in the bins, float wavelengthCount is that path's least length in
// mm (0 in the paper's model, where length does not matter), and the rest is
// padding: whole vec4s, because the march copies a row where a CPU driver
// gathers each load lane by lane, a vec4 for about a float's cost.
// One invocation per domain, in groups of:
OPAL_CONSTANT int ShadowTableGroupSize = 64;
#define SHADOW_TABLE_ROW_VEC4S(wavelengthCount) (((wavelengthCount) + 4) / 4)

// The view march's result per pixel: CIE XYZ and the distance from the eye to
// the surface (0 where the ray misses).
struct OPAL_ALIGNED PixelColour
{
  OPAL_ALIGNED vec3 xyz;
  float depth;
};

// Where the mirror image of a pixel's primary ray in the surface passes
// closest to the light's centre (valid 0: it misses the opal or points
// away); the view march writes it, the highlight pass reads it.
struct OPAL_ALIGNED PixelMirror
{
  OPAL_ALIGNED vec3 nearLight;
  int valid;
};

// A pixel's rays summed by the view march (docs/design.md §3.4): their XYZ,
// the nearest surface (0: none met yet), the brightest diffraction's
// wavelength, luminance Y and domain (-1: none), and how many met the opal.
// The refine of an edge pixel marches one sub-ray per dispatch and keeps
// these between them, and what its first PixelSamples sub-rays saw: the
// first's first and brightest domains (-2: it missed) and whether all of
// them saw the same (then they stand for the pixel).
struct OPAL_ALIGNED PixelSum
{
  OPAL_ALIGNED vec3 xyz;
  float depth;
  float dominantLambda;
  float dominantY;
  int dominantDomain;
  int hits;
  int firstDomainSeen;
  int brightestDomainSeen;
  int alike;
};

// The view march's Bragg result per pixel, and what its edge select compares.
struct PixelBragg
{
  float dominantWavelength;           // nm of the brightest diffraction, 0 if none
  int dominantDomain;                 // the domain it comes from, -1 if none
  float coverage;                     // the share of the pixel's rays that meet the opal (one ray: 1 or 0)
  int firstDomain;                    // the first domain the centre ray's refracted ray crosses, -1 if none
};

// The light pass's modes, one pipeline each (LightPassModeConstant).
OPAL_CONSTANT int LightPassMarchTowardsLight = 0; // each voxel marches to the light
OPAL_CONSTANT int LightPassSweepFromAbove = 1;    // one layer from the layer above
OPAL_CONSTANT int LightPassMarchQueued = 2;       // the skin voxels the sweep queued: each marches to the light
OPAL_CONSTANT int LightPassScatteredField = 3;    // each voxel's every-order field from the tally grid (§3.10)

// Rare, costly work queued by one dispatch for a dispatch of its own (a CPU
// driver runs a branch's code for every SIMD lane): the indirect dispatch's
// workgroups (x, y, z) and how many items are queued. The light pass queues
// a layer's skin voxels (each walked to the light exactly); the highlight pass the pixels near the light's mirror
// image (sub-rays traced to the surface).
struct DispatchQueue
{
  uint groupsX;
  uint groupsY;
  uint groupsZ;
  uint count;
};

// The device addresses of the per-voxel fields and the every-order tally
// grid (low word, high word), for the passes compiled with OPAL_VOLUME_ADDRESSES.
struct VolumeAddresses
{
  uvec2 voxelCells;
  uvec2 surfaceDistance;
  uvec2 lightField;
  uvec2 lightAbsorption;
  uvec2 absorptionCells;
  uvec2 lightShadow;
  uvec2 entryVoxels;
  uvec2 scatteredLight;
  uvec2 scatteredLightGrid; // the every-order field's tally grid, not per voxel
  uvec2 surfaceTiles;       // the highlight's SurfaceDistance: per tile, not per voxel
  uvec2 surfaceTileValues;
};

// Push constants of the light pass: the voxels [first, first + count) in
// LightPassMarchTowardsLight and LightPassScatteredField (first unsigned: a
// grid holds up to 2^32 - 1 voxels, docs/design.md §3.7); the layer y = layer
// in the other two modes, LightPassSweepFromAbove sweeping its rows
// z = first to first + count - 1 (a share of the layer, docs/design.md §8.1),
// LightPassMarchQueued the layer's queue (count 0) or, taking up another
// share's queued walks in a pass shared by processes, `count` of them.
// A forwarded walk to the light (§8.1) walks only within layers z in
// [piece.x, piece.y), each walk kept where it needs another piece and taken
// up again by a later dispatch of the same voxels (`resumed` 1); the last
// (`last` 1) counts the walks still kept (ForwardedLeftBinding). A walk's
// state is slot slotFirst + its invocation: a pass shared by processes keeps
// every share's walks in one buffer, each share's from its own first slot.
struct LightPassWork
{
  uint first;
  int count;
  int layer;
  int resumed;
  ivec2 piece;
  int last;
  int slotFirst;
};

// Invocations per workgroup of the light pass.
OPAL_CONSTANT int LightPassGroupSize = 256;

// The view march's modes (docs/design.md §3.4), chosen per dispatch by its
// push constants: one pipeline holds them all, so the march's code is built once.
OPAL_CONSTANT int MarchPixels = 0;      // one ray through each pixel's centre of a band
OPAL_CONSTANT int MarchRing = 1;        // the same for the ring of pixels around the rectangle
OPAL_CONSTANT int MarchSelectEdges = 2; // every pixel: queue those whose footprint crosses an edge
OPAL_CONSTANT int MarchRefineEdges = 3; // the queued pixels: the mean of PixelSamples^2 sub-rays
// Pixels of the ring around a rectangle of width x height (MarchRing).
#define MARCH_RING_PIXELS(width, height) (2 * ((width) + 2) + 2 * (height))

// Push constants of the view march: its mode; with MarchPixels the first
// pixel, in the rendered rectangle, of the band of rows this dispatch covers
// (MarchSelectEdges: of the columns); with MarchRefineEdges the queued
// pixels [first, first + count) this dispatch refines by their sub-ray
// `subRay` (of PixelSamples^2, row by row). A forwarded march (§8.1)
// marches only within layers z in [piece.x, piece.y) of the volume, each ray
// saved where it leaves them and taken up again by a later dispatch of the
// same work (`resumed` MarchResumesRays) for the piece it enters; the last
// (`last` 1) counts the rays still kept (ForwardedLeftBinding). A march
// shared by processes (`sharesRays` 1) keeps a ray that finishes too
// (KeptUnwritten), whose pixel a dispatch of the same work writes
// (`resumed` MarchWritesFinished) once every ray has finished.
struct MarchWork
{
  ivec2 origin;
  int mode;
  int first;
  int count;
  int subRay;
  ivec2 piece;
  int resumed;
  int last;
  int sharesRays;
};
// MarchWork.resumed: the rays started, taken up where kept, or their pixels written.
OPAL_CONSTANT int MarchStartsRays = 0;
OPAL_CONSTANT int MarchResumesRays = 1;
OPAL_CONSTANT int MarchWritesFinished = 2;
// The layer word of a forwarded pass's state (opal_kept_state.glsl) once
// it needs no piece: done with (KeptDone), or a shared march's ray finished
// and kept until its pixel is written (KeptUnwritten); below both, the
// layer z whose piece takes it up.
OPAL_CONSTANT uint KeptDone = 0xffffffffu;
OPAL_CONSTANT uint KeptUnwritten = 0xfffffffeu;
// The most layers z a step of the view march's and the light pass's surface
// traces passes; a forwarded pass's piece reads SurfaceDistance
// TraceStepLayers + 2 layers beyond its own (docs/design.md §8.1).
OPAL_CONSTANT int TraceStepLayers = 4;
// The words a forwarded walk to the light keeps per voxel, exactly
// (light_optical_depth.comp's keepLightWalk and its layer word): its voxel
// among them, which a share of a shared light pass taking up another
// share's queued walk reads (its own queue holds other voxels).
OPAL_CONSTANT int LightStateWords = 33;
// The words a forwarded march keeps per ray, exactly (view_march.comp's
// keepRay and its layer word): its place, its entry and exit traces, walk and
// round, its recorded crossings, its sums and, with energy conservation, the
// last Bragg shadow it met (41 bins and 16 nodes: 1.5 KB), its mirror
// point (PixelMirror), its pixel's sums so far, and in a shared march once
// finished whether it met the opal.
#define RAY_STATE_WORDS(wavelengthCount, nodeCount) \
  (179 + 3 * (wavelengthCount) + 4 * SHADOW_TABLE_ROW_VEC4S(wavelengthCount) + 2 * (nodeCount))

// Push constants of the highlight's shade pass: the queued pixels
// [first, first + count) this dispatch shades.
struct HighlightWork
{
  int first;
  int count;
};

// PairedFields: SurfaceDistance and the light fields hold, per voxel, its
// value and its +x neighbour's (a bound trilinear read takes four loads, not
// eight); read by address, one value per voxel (float, vec2 and vec2: 12
// bytes per voxel less, 20 with absorption; docs/design.md §3.7), which one
// load reads with the next. Each pass that reads them by address takes the
// layout as a constant of its own.

// Specialisation constants, by constant_id: each pass's layout(constant_id =
// ...) and the host's pipeline keys name these ids, so neither side counts
// positions (OpalGpu's specialisation() places each value at its id).
// The light pass:
OPAL_CONSTANT int LightPassModeConstant = 0;        // int: one of the light pass's modes above
OPAL_CONSTANT int LightAbsorptionConstant = 1;      // bool: the volume absorbs (docs/design.md §3.9)
OPAL_CONSTANT int LightBraggShadowConstant = 2;     // bool: record the Bragg shadows (§7.2)
OPAL_CONSTANT int LightPairedFieldsConstant = 3;    // bool: the fields hold pairs (PairedFields)
OPAL_CONSTANT int LightForwardedConstant = 4;       // bool: walks forwarded between pieces (LightPassWork.piece)
OPAL_CONSTANT int LightPassConstantCount = 5;
// The highlight pass:
OPAL_CONSTANT int HighlightModeConstant = 0;        // int: HighlightSelect or HighlightShade
OPAL_CONSTANT int HighlightPairedFieldsConstant = 1; // bool: the fields hold pairs (PairedFields)
OPAL_CONSTANT int HighlightConstantCount = 2;
// The Bragg shadow table:
OPAL_CONSTANT int ShadowTableWavelengthsConstant = 0; // int: the frame's wavelength count
OPAL_CONSTANT int ShadowTableCoupledWaveConstant = 1; // bool: the coupled-wave model
OPAL_CONSTANT int ShadowTableConstantCount = 2;
// The view march (docs/design.md §3.4):
OPAL_CONSTANT int MarchWavelengthsConstant = 0;        // int: the frame's wavelength count
OPAL_CONSTANT int MarchSpectralNodesConstant = 1;      // int: nodes of the scattering spectrum (>= 4)
OPAL_CONSTANT int MarchExactScatteringConstant = 2;    // bool: every wavelength instead of nodes
OPAL_CONSTANT int MarchAbsorptionConstant = 3;         // bool: the volume absorbs
OPAL_CONSTANT int MarchCoupledWaveConstant = 4;        // bool: the coupled-wave Bragg model (§7.2)
OPAL_CONSTANT int MarchEnergyConservationConstant = 5; // bool: 1 - R behind a crossing
OPAL_CONSTANT int MarchFirstWavelengthConstant = 6;    // float: the first bin's centre, nm
OPAL_CONSTANT int MarchWavelengthStepConstant = 7;     // float: the bins' step, nm
OPAL_CONSTANT int MarchNearestLightConstant = 8;       // bool: the preview's per-voxel light read
OPAL_CONSTANT int MarchScatteredLightConstant = 9;     // int: the light scattered more than once (§3.10), one of
OPAL_CONSTANT int MarchScatteredLightNone = 0;         //   not added (single scattering)
OPAL_CONSTANT int MarchScatteredLightPerVoxel = 1;     //   read from the field per voxel
OPAL_CONSTANT int MarchScatteredLightFromGrid = 2;     //   evaluated from the tally grid (the field does not fit)
OPAL_CONSTANT int MarchPairedFieldsConstant = 10;      // bool: the fields hold pairs (PairedFields)
OPAL_CONSTANT int MarchForwardedConstant = 11;         // bool: rays forwarded between pieces (MarchWork.piece)
OPAL_CONSTANT int MarchConstantCount = 12;

// The march reads a LightFieldPair (and the absorption's) as one vec4,
// (voxel.x, voxel.y, nextVoxel.x, nextVoxel.y): one load where lavapipe
// gathers the struct member by member (docs/design.md §3.3). The view's
// element type; TestOpalShaderContract holds its stride to sizeof(LightFieldPair).
#define LightFieldPairAsVec4 vec4

#ifdef __cplusplus
static_assert(sizeof(RenderParameterBlock) % 16 == 0 && sizeof(WavelengthBinRecord) == 32 &&
    sizeof(DomainRecord) == 48 && sizeof(VoxelCell) == 8 && sizeof(LightShadow) == 12 && sizeof(LightFieldPair) == 16 && sizeof(DispatchQueue) == 16 && sizeof(PixelColour) == 16 && sizeof(PixelMirror) == 16 && sizeof(PixelBragg) == 16 && sizeof(PixelSum) == 48 &&
    sizeof(ScatteredLightNode) == 32,
  "std140/std430 sizes of the contract's structs");
static_assert(offsetof(LightFieldPair, voxel) == 0 && offsetof(LightFieldPair, nextVoxel) == 8 &&
    sizeof(LightFieldPair) == sizeof(LightFieldPairAsVec4),
  "a LightFieldPair is the vec4 (voxel.xy, nextVoxel.xy) the march reads");
} // namespace opal::gpu
#endif
#undef OPAL_CONSTANT
#undef OPAL_ALIGNED

#endif
