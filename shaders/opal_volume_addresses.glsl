// Per-voxel fields beyond one storage buffer's range (docs/design.md §3.7):
// compiled with OPAL_VOLUME_ADDRESSES, a pass reads and writes them through
// their device addresses (VK_KHR_buffer_device_address), which no
// maxStorageBufferRange bounds; without, through their bindings. Each field's
// accessor, NAME_AT(i), is an lvalue either way. 64-bit addresses as uvec2,
// so that no pass needs shaderInt64.
#ifdef OPAL_VOLUME_ADDRESSES
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(std430, set = 0, binding = VolumeAddressesBinding) readonly buffer VolumeAddressTable { VolumeAddresses volumeAddresses; };

// The address of element `index` of `bytes` bytes from `base`.
uvec2 voxelAddress(uvec2 base, int index, uint bytes)
{
  uint high, low;
  umulExtended(uint(index), bytes, high, low);
  uint sum = base.x + low;
  return uvec2(sum, base.y + high + (sum < low ? 1u : 0u));
}
#endif
