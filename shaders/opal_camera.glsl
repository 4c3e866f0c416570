// The camera's rays and their mirror images in the surface, shared by the
// view march and the highlight pass (docs/design.md §3.4).

vec3 primaryDirection(vec2 pixel)
{
  float width = float(P.imageWidth), height = float(P.imageHeight);
  float tanHalf = P.tanHalfViewAngle;
  vec2 ndc = vec2(2.0 * pixel.x / width - 1.0, 1.0 - 2.0 * pixel.y / height);
  return normalize(P.forward + ndc.x * tanHalf * (width / height) * P.right +
    ndc.y * tanHalf * P.up);
}

// Where the mirror image of the ray `d` at `hit` (surface normal `normal`)
// passes closest to the light's centre; w = 0 if it points away.
vec4 mirrorPointNearLight(vec3 hit, vec3 d, vec3 normal, out float cosI)
{
  cosI = -dot(d, normal);
  vec3 mirrored = reflect(d, normal);
  float along = dot(P.light - hit, mirrored);
  if (cosI <= 0.0 || along <= 0.0) return vec4(0.0);
  return vec4(hit + along * mirrored, 1.0);
}

// The same for the primary ray through `pixel`, traced from tFrom, and the
// mirror image's direction; w = 0 if the ray misses the opal.
vec4 mirrorRayNearLight(vec2 pixel, vec3 eye, float tFrom, out float cosI, out vec3 mirrored)
{
  vec3 d = primaryDirection(pixel);
  vec2 box = gridBoxHits(eye, d);
  cosI = 0.0;
  mirrored = vec3(0.0);
  if (box.x > box.y) return vec4(0.0);
  float t = traceSurfaceEntry(eye, d, max(box.x, tFrom), box.y, 0.05 * P.smallestSpacing);
  if (t < 0.0) return vec4(0.0);
  vec3 hit = eye + t * d;
  vec3 normal = surfaceNormal(hit);
  mirrored = reflect(d, normal);
  return mirrorPointNearLight(hit, d, normal, cosI);
}
