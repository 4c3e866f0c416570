// The every-order field from its coarse tally grid (docs/design.md §3.10),
// for the light pass's LightPassScatteredField and the march's MarchScatteredLightFromGrid. Needs opal_render_bindings.glsl
// (and, with OPAL_VOLUME_ADDRESSES, opal_volume_addresses.glsl) first.
#ifdef OPAL_VOLUME_ADDRESSES
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ScatteredLightNodeRef { ScatteredLightNode value; };
#define SCATTERED_LIGHT_NODE_AT(i) ScatteredLightNodeRef(voxelAddress(volumeAddresses.scatteredLightGrid, (i), 32u)).value
#else
layout(std430, set = 0, binding = ScatteredLightGridBinding) readonly buffer ScatteredLightGrid { ScatteredLightNode scatteredLightNodes[]; };
#define SCATTERED_LIGHT_NODE_AT(i) scatteredLightNodes[i]
#endif

// The light scattered more than once in voxel `cell` (docs/design.md §3.10):
// the kernel estimate of the eight tally nodes around its centre, as
// OpalScatteredLight's meanRadiance gives it (there in double precision).
// The weights come from the index: exactly 0 for a node whose cells do not
// reach the voxel.
vec4 scatteredLightAt(ivec3 cell)
{
  ivec3 nodes = P.scatteredLightNodes;
  int stride = P.scatteredLightStride;
  ivec3 c0 = min(cell / stride, max(nodes - 2, ivec3(0)));
  vec3 f = min(vec3(cell - c0 * stride) / float(stride), 1.0);
  vec4 sums = vec4(0.0);
  float volume = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    ivec3 n = min(c0 + o, nodes - 1);
    vec3 w3 = mix(1.0 - f, f, vec3(o));
    float w = w3.x * w3.y * w3.z;
    ScatteredLightNode node = SCATTERED_LIGHT_NODE_AT(n.x + nodes.x * (n.y + nodes.y * n.z));
    sums += w * node.tally;
    volume += w * node.volume;
  }
  return volume > 0.0 ? sums / volume : vec4(0.0);
}
