// A forwarded pass's states between its dispatches (docs/design.md §8.1): the
// view march's rays, the light pass's walks to the light. Each invocation
// owns `words` uints from slot * words: the first the layer z its piece must
// hold to take it up (KeptDone once done, KeptUnwritten for a shared
// march's ray finished), then what its pass keeps,
// each value written and read back bit for bit by the same keep* calls (one
// layout both ways). Needs opal_volume_fields.glsl (SurfaceTrace) and
// opal_voxel_walk.glsl.
layout(std430, set = 0, binding = RayStatesBinding) buffer KeptStates { uint keptStates[]; };
layout(std430, set = 0, binding = ForwardedLeftBinding) buffer ForwardedLeft { uint forwardedLeft; };

bool keptSaving; // the keep* calls' way: into keptStates, or out of them
int keptWord;    // their next word

// The keep* calls after this save (`saving`) or restore slot `slot`'s state
// of `words` words, after its layer word.
void beginKeeping(int slot, int words, bool saving)
{
  keptSaving = saving;
  keptWord = slot * words + 1;
}

// The layer word of slot `slot`: where it goes on, or KeptDone, KeptUnwritten.
uint keptLayer(int slot, int words)
{
  return keptStates[slot * words];
}

void keepLayer(int slot, int words, uint layer)
{
  keptStates[slot * words] = layer;
}

// Whether a state with layer word `layer` goes on in a piece.
bool keptGoesOn(uint layer)
{
  return layer < KeptUnwritten;
}

// In a forwarded pass's last dispatch (`last`), slot `slot`'s state counted
// where it is still kept: a path longer than the sweeps' schedule, which the
// host refuses (docs/design.md §8.1) rather than give its partial result.
void countUnfinished(int slot, int words, bool last)
{
  if (last && keptGoesOn(keptLayer(slot, words))) atomicAdd(forwardedLeft, 1u);
}

void keepFloat(inout float v)
{
  if (keptSaving) keptStates[keptWord] = floatBitsToUint(v);
  else v = uintBitsToFloat(keptStates[keptWord]);
  ++keptWord;
}

void keepInt(inout int v)
{
  if (keptSaving) keptStates[keptWord] = uint(v);
  else v = int(keptStates[keptWord]);
  ++keptWord;
}

void keepBool(inout bool b)
{
  int word = b ? 1 : 0;
  keepInt(word);
  b = word != 0;
}

void keepVec3(inout vec3 v)
{
  keepFloat(v.x);
  keepFloat(v.y);
  keepFloat(v.z);
}

void keepIvec3(inout ivec3 v)
{
  keepInt(v.x);
  keepInt(v.y);
  keepInt(v.z);
}

void keepShadow(inout LightShadow shadow)
{
  keepInt(shadow.domain);
  keepFloat(shadow.lengthMm);
  keepFloat(shadow.ownLengthMm);
}

void keepTrace(inout SurfaceTrace trace)
{
  keepFloat(trace.t);
  keepFloat(trace.previous);
  keepInt(trace.steps);
  keepBool(trace.done);
}

// A cell walk along `direction`: its steps set again from it (setWalkSteps).
void keepVoxelWalk(inout VoxelWalk walk, vec3 direction)
{
  keepIvec3(walk.cell);
  keepVec3(walk.tMax);
  if (!keptSaving) setWalkSteps(walk, direction);
}
