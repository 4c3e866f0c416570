#version 450
// HighlightPass (docs/design.md §3.4): the Fresnel reflection of the light
// seen in the surface (the paper's specular term and its secondary ray in the
// mirror direction: the scene holds nothing else to reflect), added to the
// pixels the view march wrote. Where the mirror rays of this pixel and of
// its right and lower neighbours (ray differentials, which the march
// recorded) pass within reach of the light, the pixel takes its share of
// the light's image: found by Newton's method where the image is no larger
// than the pixel (the usual case), else from n x n sub-rays; elsewhere
// nothing is added. Two
// dispatches of this shader (specialisation constant 0): HighlightSelect over
// every pixel reads what the march recorded and queues the pixels that may
// see the light (and those at the rectangle's edge, whose neighbour it must
// trace); HighlightShade supersamples only those, in dispatches of the
// queue's items the host sizes (no submit runs long).
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = HighlightGroupSize) in;
layout(constant_id = HighlightModeConstant) const int HIGHLIGHT_MODE = HighlightSelect;
#define PAIRED_FIELDS_CONSTANT HighlightPairedFieldsConstant
// The surface from its tiles, which every process holds whole (docs/design.md §3.4).
#define SURFACE_TILES
#include "opal_volume_fields.glsl"
#include "opal_optics.glsl"
#include "opal_camera.glsl"

layout(std430, set = 0, binding = PixelColourBinding) buffer PixelColourImage { PixelColour pixelColour[]; };
layout(std430, set = 0, binding = PixelBraggBinding) readonly buffer PixelBraggImage { PixelBragg pixelBragg[]; };
layout(std430, set = 0, binding = PixelSpectrumBinding) buffer PixelSpectrum { float pixelSpectrum[]; };
layout(std430, set = 0, binding = PixelMirrorBinding) readonly buffer PixelMirrorImage { PixelMirror pixelMirror[]; };
layout(std430, set = 0, binding = HighlightQueueBinding) buffer HighlightQueue { DispatchQueue queue; }; // its count
layout(push_constant) uniform HighlightPush { HighlightWork highlightWork; };
layout(std430, set = 0, binding = HighlightPixelsBinding) buffer HighlightPixels { uint queuedPixels[]; };

// The mirror point of the primary ray through the pixel `offset` from
// `local` in the rectangle: recorded by the march inside the rectangle,
// traced here beyond its edge.
vec4 neighbourMirror(ivec2 local, ivec2 offset, vec2 pixel, float tFrom)
{
  ivec2 next = local + offset;
  if (next.x < P.rectSize.x && next.y < P.rectSize.y)
  {
    PixelMirror m = pixelMirror[next.x + P.rectSize.x * next.y];
    return vec4(m.nearLight, float(m.valid));
  }
  if (HIGHLIGHT_MODE == HighlightSelect)
  {
    return vec4(0.0); // not reached: pixels at the edge are queued unseen
  }
  float cosI;
  vec3 mirrored;
  return mirrorRayNearLight(pixel + vec2(offset), P.eye, tFrom, cosI, mirrored);
}

// Sub-rays per pixel axis, at most: a first pass of up to 16 and, where the
// light image's edge crosses the pixel, a second of up to 32. lavapipe (the
// tests' device) ends every loop of a shader invocation once all its loops
// together have run 65535 iterations (Mesa's gallivm loop limiter, counted
// per SIMD batch of 8 pixels), silently: at 64 x 64 sub-rays of ~20
// iterations each (the surface's sphere tracing and 12 bisections) the
// limiter ran out and the wavelength loop that adds the highlight ran once,
// so the highlight vanished at 16 x 12, 32 x 24, 120 x 90 and other image
// sizes of the 40 x 20 x 50 opal. 16^2 + 32^2 sub-rays stay near 26000.
const int FirstPassMost = 16, EdgePassMost = 32;

// The share of a sub-ray's cell (area `cellArea` where the mirror rays pass
// the light) that the light's disc covers, the sub-ray's mirror ray passing
// at distance d from the light's centre: the overlap of the disc with a disc
// of the cell's area (the lens of two circles), over that area. Filtering
// each sub-ray this way makes n x n sub-rays converge on the pixel's true
// coverage far faster than point samples, whose edge pixels jump by 1/n^2.
float discCoverage(float d, float cellArea)
{
  float r = P.lightRadius;
  if (cellArea <= 0.0)
  {
    return d <= r ? 1.0 : 0.0; // no ray differentials: a point sample
  }
  float rho = sqrt(cellArea / OPAL_PI);
  if (d >= r + rho) return 0.0;
  if (d <= abs(r - rho)) return min(r, rho) * min(r, rho) * OPAL_PI / cellArea;
  float lens = r * r * acos(clamp((d * d + r * r - rho * rho) / (2.0 * d * r), -1.0, 1.0)) +
    rho * rho * acos(clamp((d * d + rho * rho - r * r) / (2.0 * d * rho), -1.0, 1.0)) -
    0.5 * sqrt(max((-d + r + rho) * (d + r - rho) * (d - r + rho) * (d + r + rho), 0.0));
  return lens / cellArea;
}

// The Fresnel reflectance averaged over n x n sub-rays of the pixel, whose
// mirror rays sweep `pixelArea` near the light; y is 1 where the light's
// image covers the pixel only in part (its edge crosses it).
vec2 supersampledHighlight(vec2 pixel, float tFrom, float pixelArea, int n)
{
  float cellArea = pixelArea / float(n * n);
  float sum = 0.0;
  float least = 1.0, most = 0.0;
  for (int sy = 0; sy < n; ++sy)
  {
    for (int sx = 0; sx < n; ++sx)
    {
      vec2 sub = pixel - 0.5 + (vec2(sx, sy) + 0.5) / float(n);
      float cosI;
      vec3 mirrored;
      vec4 near = mirrorRayNearLight(sub, P.eye, tFrom, cosI, mirrored);
      float covered = near.w > 0.0 ? discCoverage(distance(near.xyz, P.light), cellArea) : 0.0;
      least = min(least, covered);
      most = max(most, covered);
      sum += covered * fresnelReflectance(cosI, P.refractiveIndex);
    }
  }
  return vec2(sum / float(n * n), most > 0.0 && least < 1.0 ? 1.0 : 0.0);
}

// Where the mirror image of the primary ray through image point q crosses
// the plane through the light perpendicular to `axis`; w = 0 if it misses.
vec4 mirrorRayAtLight(vec2 q, float tFrom, vec3 axis)
{
  float cosI;
  vec3 mirrored;
  vec4 near = mirrorRayNearLight(q, P.eye, tFrom, cosI, mirrored);
  float across = dot(mirrored, axis);
  return near.w > 0.0 && across > 0.0 ? vec4(near.xyz + mirrored * dot(P.light - near.xyz, axis) / across, 1.0)
                                      : vec4(0.0);
}

// The light image's centre: the image point q whose mirror ray passes
// through the light's centre, by Newton's method from the pixel's centre on
// the mirror map (central differences over a sixteenth of a pixel, in the
// plane through the light perpendicular to the mirror ray). On return `a`,
// `b` are how the mirror ray moves there per pixel in x and y; false where
// a ray misses or the iteration does not settle within 0.001 pixel.
bool lightImageCentre(vec2 pixel, float tFrom, out vec2 q, out vec3 a, out vec3 b, out float cosI)
{
  const float h = 1.0 / 16.0;
  q = pixel;
  for (int k = 0; k < 8; ++k)
  {
    vec3 mirrored;
    vec4 near = mirrorRayNearLight(q, P.eye, tFrom, cosI, mirrored);
    vec4 left = mirrorRayAtLight(q - vec2(h, 0.0), tFrom, mirrored);
    vec4 right = mirrorRayAtLight(q + vec2(h, 0.0), tFrom, mirrored);
    vec4 up = mirrorRayAtLight(q - vec2(0.0, h), tFrom, mirrored);
    vec4 down = mirrorRayAtLight(q + vec2(0.0, h), tFrom, mirrored);
    if (near.w * left.w * right.w * up.w * down.w == 0.0)
    {
      return false;
    }
    a = (right.xyz - left.xyz) / (2.0 * h);
    b = (down.xyz - up.xyz) / (2.0 * h);
    vec3 offset = P.light - near.xyz; // perpendicular to the mirror ray, as a and b
    float aa = dot(a, a), ab = dot(a, b), bb = dot(b, b);
    vec2 step = vec2(bb * dot(a, offset) - ab * dot(b, offset), aa * dot(b, offset) - ab * dot(a, offset)) /
      max(aa * bb - ab * ab, 1e-30);
    q += clamp(step, -2.0, 2.0);
    if (length(step) < 1e-3)
    {
      return true;
    }
  }
  return false;
}

// The highlight of a light image no larger than a pixel: its centre found
// (lightImageCentre) and the image, as a square of its area, overlapped
// with the pixel. Every pixel around finds the same centre, so the pixels'
// shares tile the image exactly wherever it falls, a corner of four pixels
// included; sub-rays filtered as discs of their cell's area (below) missed
// an image smaller than a cell at a cell's corner, as in this paper's set-up
// (light = eye above the apex) at every even image size.
float smallImageHighlight(vec2 pixel, float tFrom)
{
  vec2 q;
  vec3 a, b;
  float cosI;
  if (!lightImageCentre(pixel, tFrom, q, a, b, cosI))
  {
    return 0.0;
  }
  float side = sqrt(OPAL_PI * P.lightRadius * P.lightRadius / max(length(cross(a, b)), 1e-30));
  vec2 u = q - pixel;
  vec2 overlap = clamp(min(u + 0.5 * side, 0.5) - max(u - 0.5 * side, -0.5), 0.0, 1.0);
  return overlap.x * overlap.y * fresnelReflectance(cosI, P.refractiveIndex);
}

// The highlight's share of the pixel. A light image no larger than the
// pixel: smallImageHighlight. A larger one: n x n sub-rays, n
// SpecularSamples or more until a cell is at most half the light's radius
// wide (up to FirstPassMost); where the image's edge crosses the pixel,
// again with four times n per axis (up to EdgePassMost), so edge pixels
// converge like the rest. No ray differentials (the silhouette): point
// samples.
float pixelHighlight(vec2 pixel, float tFrom, vec3 dx, vec3 dy)
{
  float pixelArea = length(cross(dx, dy));
  if (OPAL_PI * P.lightRadius * P.lightRadius <= pixelArea)
  {
    return smallImageHighlight(pixel, tFrom);
  }
  float spread = max(length(dx), length(dy));
  int n = clamp(int(ceil(2.0 * spread / P.lightRadius)), P.specularSamples, max(P.specularSamples, FirstPassMost));
  vec2 highlight = supersampledHighlight(pixel, tFrom, pixelArea, n);
  if (highlight.y > 0.0 && n < EdgePassMost)
  {
    highlight = supersampledHighlight(pixel, tFrom, pixelArea, min(4 * n, EdgePassMost));
  }
  return highlight.x;
}

// Where the mirror rays of the pixel and its right and lower neighbours
// pass near the light (ray differentials): whether they come within reach
// of it, and how far the mirror rays move there from this pixel to the
// next in x and in y (0 where a neighbour misses: sub-rays then decide as
// point samples). `onlyRecorded`: the neighbours beyond the rectangle's
// edge count as within reach (HighlightShade traces them).
struct Reach
{
  bool near;
  vec3 dx, dy;
};

Reach reachOfLight(ivec2 local, int pixelIndex, bool onlyRecorded)
{
  PixelMirror centre = pixelMirror[pixelIndex];
  if (pixelBragg[pixelIndex].coverage == 0.0 || centre.valid == 0)
  {
    return Reach(false, vec3(0.0), vec3(0.0));
  }
  bool edge = local.x + 1 >= P.rectSize.x || local.y + 1 >= P.rectSize.y;
  if (onlyRecorded && edge)
  {
    return Reach(true, vec3(0.0), vec3(0.0));
  }
  vec2 pixel = vec2(P.rectOrigin + local) + 0.5;
  float tFrom = pixelColour[pixelIndex].depth - 4.0 * P.smallestSpacing;
  vec4 nextX = neighbourMirror(local, ivec2(1, 0), pixel, tFrom);
  vec4 nextY = neighbourMirror(local, ivec2(0, 1), pixel, tFrom);
  if (nextX.w == 0.0 || nextY.w == 0.0)
  {
    return Reach(true, vec3(0.0), vec3(0.0)); // at the silhouette
  }
  vec3 dx = nextX.xyz - centre.nearLight, dy = nextY.xyz - centre.nearLight;
  float spread = max(length(dx), length(dy));
  return Reach(distance(centre.nearLight, P.light) <= P.lightRadius + 1.5 * spread, dx, dy);
}

// Adds the supersampled highlight to a queued pixel: the light's normalised
// D65, reflected, to its XYZ and its spectrum.
void shade(ivec2 local, int pixelIndex)
{
  Reach reach = reachOfLight(local, pixelIndex, false);
  if (!reach.near)
  {
    return;
  }
  vec2 pixel = vec2(P.rectOrigin + local) + 0.5;
  float tFrom = pixelColour[pixelIndex].depth - 4.0 * P.smallestSpacing;
  float highlight = pixelHighlight(pixel, tFrom, reach.dx, reach.dy) * P.lightRadiance;
  vec3 xyz = vec3(0.0);
  for (int l = 0; l < P.wavelengthCount; ++l)
  {
    float value = highlight * bins[l].illuminant;
    xyz += value * bins[l].colourMatching * bins[l].width;
    if (P.writeSpectrum != 0) pixelSpectrum[pixelIndex * P.wavelengthCount + l] += value;
  }
  pixelColour[pixelIndex].xyz += xyz;
}

void main()
{
  int item = passItem(HighlightGroupSize);
  if (HIGHLIGHT_MODE == HighlightSelect)
  {
    if (item >= P.rectSize.x * P.rectSize.y) return;
    ivec2 local = ivec2(item % P.rectSize.x, item / P.rectSize.x);
    if (reachOfLight(local, item, true).near)
    {
      queuedPixels[atomicAdd(queue.count, 1u)] = uint(item);
    }
    return;
  }
  item += highlightWork.first;
  if (item >= highlightWork.first + highlightWork.count || item >= int(queue.count)) return;
  int pixelIndex = int(queuedPixels[item]);
  shade(ivec2(pixelIndex % P.rectSize.x, pixelIndex / P.rectSize.x), pixelIndex);
}
