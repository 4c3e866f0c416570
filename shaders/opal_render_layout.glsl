// Buffers and parameters shared by every Opal render pass. One descriptor set
// layout serves all passes (bindings 0-12); each pass declares what it uses.
// The parameters are a uniform block: read-only and never aliased by the
// storage buffers, so compilers keep them in registers.
// Lengths are in mm, wavelengths in nm, all positions in the model's frame.

struct RenderParameters
{
  ivec4 gridDims;       // voxels x, y, z; w = number of wavelengths
  vec4 gridOrigin;      // centre of voxel (0,0,0); w = smallest spacing
  vec4 gridSpacing;     // xyz; w = march step (mm)
  vec4 eye;             // xyz; w = tan(half vertical view angle)
  vec4 forward;         // unit view direction; w = 1 if the Spectrum array is written
  vec4 right;           // unit image x; w = image width (pixels)
  vec4 up;              // unit image y; w = image height (pixels)
  vec4 light;           // xyz; w = light radius
  ivec4 rect;           // rendered sub-rectangle: x0, y0, width, height
  vec4 optics;          // refractive index mu, Bragg bandwidth (relative), diffraction gain, mosaic spread (rad)
  vec4 lighting;        // apex distance^2 (irradiance 1 at the apex), light radiance, fall-off at L_in (paper eq. 6) flag, specular samples per axis
  ivec4 counts;         // domain count, Bragg orders, unused, unused
  vec4 colour;          // exposure, unused, unused, unused
  vec4 background;      // linear sRGB of the background; w = 8-bit flag unused
};

layout(std140, set = 0, binding = 0) uniform ParameterBlock { RenderParameters P; };

// Per wavelength i: W[2i] = (lambda, (550/lambda)^4, normalised D65, bin width),
// W[2i+1] = bin-averaged CIE 1931 x-bar, y-bar, z-bar.
layout(std430, set = 0, binding = 1) readonly buffer WavelengthTable { vec4 W[]; };
