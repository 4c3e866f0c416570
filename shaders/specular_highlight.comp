#version 450
// HighlightPass (docs/design.md §3.4): the Fresnel reflection of the light
// seen in the surface (the paper's specular term and its secondary ray in the
// mirror direction: the scene holds nothing else to reflect), added to the
// pixels the view march wrote. The light is often smaller than a pixel, so
// where the mirror rays of this pixel and of its right and lower neighbours
// (ray differentials, which the march recorded) pass within reach of it,
// n x n sub-rays cover the pixel; elsewhere nothing is added. Two
// dispatches of this shader (specialisation constant 0): HighlightSelect over
// every pixel reads what the march recorded and queues the pixels that may
// see the light (and those at the rectangle's edge, whose neighbour it must
// trace); HighlightShade supersamples only those, in dispatches of the
// queue's items the host sizes (no submit runs long).
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = HighlightGroupSize) in;
layout(constant_id = HighlightModeConstant) const int HIGHLIGHT_MODE = HighlightSelect;
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
  return mirrorRayNearLight(pixel + vec2(offset), P.eye, tFrom, cosI);
}

// The share of a sub-ray's cell (area `cellArea` where the mirror rays pass
// the light) that the light's disc covers, the sub-ray's mirror ray passing
// at distance d from the light's centre: the overlap of the disc with a disc
// of the cell's area (the lens of two circles), over that area. Filtering
// each sub-ray this way makes n x n sub-rays converge on the pixel's true
// coverage far faster than point samples, whose edge pixels jump by 1/n^2,
// and holds for a light image smaller than a sub-ray's cell as for a larger.
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
// mirror rays sweep `pixelArea` near the light (0: unknown); y is 1 where
// the light's image covers the pixel only in part (its edge crosses it).
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
      vec4 near = mirrorRayNearLight(sub, P.eye, tFrom, cosI);
      float covered = near.w > 0.0 ? discCoverage(distance(near.xyz, P.light), cellArea) : 0.0;
      least = min(least, covered);
      most = max(most, covered);
      sum += covered * fresnelReflectance(cosI, P.refractiveIndex);
    }
  }
  return vec2(sum / float(n * n), most > 0.0 && least < 1.0 ? 1.0 : 0.0);
}

// The highlight's share of the pixel: n x n sub-rays, n SpecularSamples or
// more where a sub-ray's cell would be wider than half the light's radius (a
// light image smaller than the sub-rays' spacing, as at small image sizes);
// where the image's edge crosses the pixel, again with four times n per axis
// (up to 64), so edge pixels converge like the rest.
float pixelHighlight(vec2 pixel, float tFrom, vec2 reach)
{
  int n = clamp(int(ceil(2.0 * reach.x / P.lightRadius)), P.specularSamples, max(P.specularSamples, 64));
  vec2 highlight = supersampledHighlight(pixel, tFrom, reach.y, n);
  if (highlight.y > 0.0 && 4 * n <= 64)
  {
    highlight = supersampledHighlight(pixel, tFrom, reach.y, 4 * n);
  }
  return highlight.x;
}

// Where the mirror rays of the pixel and its right and lower neighbours
// pass near the light (ray differentials): x how far apart (-1 where they do
// not come within reach of the light), y the area the pixel's mirror rays
// sweep there (0 where a neighbour misses: sub-rays then decide as point
// samples). `onlyRecorded`: the neighbours beyond the rectangle's edge count
// as within reach (HighlightShade traces them).
vec2 reachOfLight(ivec2 local, int pixelIndex, bool onlyRecorded)
{
  PixelMirror centre = pixelMirror[pixelIndex];
  if (pixelBragg[pixelIndex].coverage == 0.0 || centre.valid == 0)
  {
    return vec2(-1.0, 0.0);
  }
  bool edge = local.x + 1 >= P.rectSize.x || local.y + 1 >= P.rectSize.y;
  if (onlyRecorded && edge)
  {
    return vec2(0.0);
  }
  vec2 pixel = vec2(P.rectOrigin + local) + 0.5;
  float tFrom = pixelColour[pixelIndex].depth - 4.0 * P.smallestSpacing;
  vec4 nextX = neighbourMirror(local, ivec2(1, 0), pixel, tFrom);
  vec4 nextY = neighbourMirror(local, ivec2(0, 1), pixel, tFrom);
  if (nextX.w == 0.0 || nextY.w == 0.0)
  {
    return vec2(0.0); // at the silhouette
  }
  vec3 dx = nextX.xyz - centre.nearLight, dy = nextY.xyz - centre.nearLight;
  float spread = max(length(dx), length(dy));
  bool near = distance(centre.nearLight, P.light) <= P.lightRadius + 1.5 * spread;
  return vec2(near ? spread : -1.0, length(cross(dx, dy)));
}

// Adds the supersampled highlight to a queued pixel: the light's normalised
// D65, reflected, to its XYZ and its spectrum.
void shade(ivec2 local, int pixelIndex)
{
  vec2 reach = reachOfLight(local, pixelIndex, false);
  if (reach.x < 0.0)
  {
    return;
  }
  vec2 pixel = vec2(P.rectOrigin + local) + 0.5;
  float tFrom = pixelColour[pixelIndex].depth - 4.0 * P.smallestSpacing;
  float highlight = pixelHighlight(pixel, tFrom, reach) * P.lightRadiance;
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
    if (reachOfLight(local, item, true).x >= 0.0)
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
