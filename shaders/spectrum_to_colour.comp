#version 450
// SpectrumToColourPass (docs/design.md §3.5): CIE XYZ (already integrated
// from the spectrum with the CIE 1931 2-degree tables) -> linear sRGB (D65)
// -> exposure -> hue-preserving tone map -> sRGB transfer -> 8 bit.
#extension GL_GOOGLE_include_directive : require

#include "opal_render_bindings.glsl"

layout(local_size_x = ColourGroupSize) in;

layout(std430, set = 0, binding = PixelColourBinding) readonly buffer PixelColourImage { PixelColour pixelColour[]; };
layout(std430, set = 0, binding = PixelBraggBinding) readonly buffer PixelBraggImage { PixelBragg pixelBragg[]; };
// Linear sRGB radiance (before exposure) and packed 8-bit sRGB per pixel.
layout(std430, set = 0, binding = PixelRadianceBinding) writeonly buffer PixelRadiance { float pixelRadiance[]; };
layout(std430, set = 0, binding = PixelRGB8Binding) writeonly buffer PixelRGB8 { uint pixelRGB8[]; };

// IEC 61966-2-1 XYZ (D65) to linear sRGB.
const mat3 XYZ_TO_SRGB = mat3(3.2404542, -0.9692660, 0.0556434,
                              -1.5371385, 1.8760108, -0.2040259,
                              -0.4985314, 0.0415560, 1.0572252);

float srgbTransfer(float linear)
{
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

// Brings a colour into [0, 1]^3 keeping its hue: out-of-gamut negatives are
// desaturated towards the colour's luminance, then an over-bright colour is
// scaled down as a whole (per-channel clipping would turn orange into yellow).
vec3 huePreservingToneMap(vec3 rgb)
{
  float luminance = dot(rgb, vec3(0.2126, 0.7152, 0.0722));
  float lowest = min(rgb.r, min(rgb.g, rgb.b));
  if (lowest < 0.0 && luminance > 0.0)
  {
    rgb = luminance + (rgb - luminance) * (luminance / (luminance - lowest));
  }
  rgb = max(rgb, vec3(0.0));
  float highest = max(rgb.r, max(rgb.g, rgb.b));
  return highest > 1.0 ? rgb / highest : rgb;
}

void main()
{
  int index = passItem(ColourGroupSize);
  if (index >= P.rectSize.x * P.rectSize.y)
  {
    return;
  }
  // A pixel the outline crosses holds the opal's light over the share
  // `coverage` of its area (docs/design.md §3.4), the background over the
  // rest: its radiance adds the background's share; its display is the mean
  // of what the two parts would display (the opal's part tone-mapped at its
  // own brightness, the linear XYZ over the coverage).
  float coverage = pixelBragg[index].coverage;
  vec3 linear = XYZ_TO_SRGB * pixelColour[index].xyz;
  vec3 background = clamp(P.background, 0.0, 1.0);
  vec3 opal = coverage > 0.0 ? huePreservingToneMap(linear * (P.exposure / coverage)) : vec3(0.0);
  vec3 display = coverage * opal + (1.0 - coverage) * background;
  vec3 radiance = linear + (1.0 - coverage) * P.background;
  for (int c = 0; c < 3; ++c) pixelRadiance[3 * index + c] = radiance[c];
  uvec3 bytes = uvec3(round(255.0 * vec3(srgbTransfer(display.r), srgbTransfer(display.g),
    srgbTransfer(display.b))));
  pixelRGB8[index] = bytes.r | (bytes.g << 8) | (bytes.b << 16);
}
