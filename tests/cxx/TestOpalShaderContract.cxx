// The host-shader contract (shaders/opal_render_contract.h, docs/design.md
// §3.8) lays out every field at the same offset on both sides: glslang's
// reflection of each compiled pass against the C++ offsetof and sizeof of the
// same header. A field that one side would place differently, or a field the
// table below does not check, fails.
// Usage: TestOpalShaderContract GLSLANG_VALIDATOR SHADER_DIR
#include "OpalTestHarness.h"
#include "opal_render_contract.h"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using namespace opal::gpu;

// GLSL member name as the reflection spells it -> C++ offset.
const std::map<std::string, std::size_t>& expectedOffsets()
{
#define OPAL_FIELD(prefix, type, field) { std::string(prefix) + #field, offsetof(type, field) }
  static const std::map<std::string, std::size_t> table = {
    OPAL_FIELD("P.", RenderParameterBlock, gridDimensions),
    OPAL_FIELD("P.", RenderParameterBlock, wavelengthCount),
    OPAL_FIELD("P.", RenderParameterBlock, gridOrigin),
    OPAL_FIELD("P.", RenderParameterBlock, smallestSpacing),
    OPAL_FIELD("P.", RenderParameterBlock, gridSpacing),
    OPAL_FIELD("P.", RenderParameterBlock, marchStep),
    OPAL_FIELD("P.", RenderParameterBlock, eye),
    OPAL_FIELD("P.", RenderParameterBlock, tanHalfViewAngle),
    OPAL_FIELD("P.", RenderParameterBlock, forward),
    OPAL_FIELD("P.", RenderParameterBlock, writeSpectrum),
    OPAL_FIELD("P.", RenderParameterBlock, right),
    OPAL_FIELD("P.", RenderParameterBlock, imageWidth),
    OPAL_FIELD("P.", RenderParameterBlock, up),
    OPAL_FIELD("P.", RenderParameterBlock, imageHeight),
    OPAL_FIELD("P.", RenderParameterBlock, light),
    OPAL_FIELD("P.", RenderParameterBlock, lightRadius),
    OPAL_FIELD("P.", RenderParameterBlock, background),
    OPAL_FIELD("P.", RenderParameterBlock, exposure),
    OPAL_FIELD("P.", RenderParameterBlock, rectOrigin),
    OPAL_FIELD("P.", RenderParameterBlock, rectSize),
    OPAL_FIELD("P.", RenderParameterBlock, refractiveIndex),
    OPAL_FIELD("P.", RenderParameterBlock, braggBandwidth),
    OPAL_FIELD("P.", RenderParameterBlock, diffractionGain),
    OPAL_FIELD("P.", RenderParameterBlock, mosaicSpread),
    OPAL_FIELD("P.", RenderParameterBlock, apexDistanceSquared),
    OPAL_FIELD("P.", RenderParameterBlock, lightRadiance),
    OPAL_FIELD("P.", RenderParameterBlock, lightFalloffAtEntry),
    OPAL_FIELD("P.", RenderParameterBlock, specularSamples),
    OPAL_FIELD("P.", RenderParameterBlock, pixelSamples),
    OPAL_FIELD("P.", RenderParameterBlock, domainCount),
    OPAL_FIELD("P.", RenderParameterBlock, braggOrders),
    OPAL_FIELD("P.", RenderParameterBlock, absorptionExponent),
    OPAL_FIELD("P.", RenderParameterBlock, meanIndex),
    OPAL_FIELD("P.", RenderParameterBlock, permittivityContrast),
    OPAL_FIELD("P.", RenderParameterBlock, coherentLayers),
    OPAL_FIELD("P.", RenderParameterBlock, latticeFamilies),
    OPAL_FIELD("P.", RenderParameterBlock, maxGroupsX),
    OPAL_FIELD("P.", RenderParameterBlock, scatteredLightNodes),
    OPAL_FIELD("P.", RenderParameterBlock, scatteredLightStride),
    OPAL_FIELD("P.", RenderParameterBlock, heldFirstVoxel),
    OPAL_FIELD("P.", RenderParameterBlock, mediumFirstVoxel),
    OPAL_FIELD("bins[0].", WavelengthBinRecord, lambda),
    OPAL_FIELD("bins[0].", WavelengthBinRecord, width),
    OPAL_FIELD("bins[0].", WavelengthBinRecord, rayleighScale),
    OPAL_FIELD("bins[0].", WavelengthBinRecord, illuminant),
    OPAL_FIELD("bins[0].", WavelengthBinRecord, colourMatching),
    OPAL_FIELD("queues[0].", DispatchQueue, groupsX),
    OPAL_FIELD("queues[0].", DispatchQueue, groupsY),
    OPAL_FIELD("queues[0].", DispatchQueue, groupsZ),
    OPAL_FIELD("queues[0].", DispatchQueue, count),
    OPAL_FIELD("lightField[0].", LightFieldPair, voxel),
    OPAL_FIELD("lightField[0].", LightFieldPair, nextVoxel),
    OPAL_FIELD("lightAbsorption[0].", LightFieldPair, voxel),
    OPAL_FIELD("lightAbsorption[0].", LightFieldPair, nextVoxel),
    OPAL_FIELD("lightShadow[0].", LightShadow, domain),
    OPAL_FIELD("lightShadow[0].", LightShadow, lengthMm),
    OPAL_FIELD("lightShadow[0].", LightShadow, ownLengthMm),
    OPAL_FIELD("scatteredLightNodes[0].", ScatteredLightNode, tally),
    OPAL_FIELD("scatteredLightNodes[0].", ScatteredLightNode, volume),
    OPAL_FIELD("domains[0].", DomainRecord, latticeNormal),
    OPAL_FIELD("domains[0].", DomainRecord, planeSpacing),
    OPAL_FIELD("domains[0].", DomainRecord, orientation),
    OPAL_FIELD("domains[0].", DomainRecord, centre),
    OPAL_FIELD("domains[0].", DomainRecord, unused),
    OPAL_FIELD("pixelColour[0].", PixelColour, xyz),
    OPAL_FIELD("pixelColour[0].", PixelColour, depth),
    OPAL_FIELD("pixelMirror[0].", PixelMirror, nearLight),
    OPAL_FIELD("pixelMirror[0].", PixelMirror, valid),
    OPAL_FIELD("pixelBragg[0].", PixelBragg, dominantWavelength),
    OPAL_FIELD("pixelBragg[0].", PixelBragg, dominantDomain),
    OPAL_FIELD("pixelBragg[0].", PixelBragg, coverage),
    OPAL_FIELD("pixelBragg[0].", PixelBragg, firstDomain),
    OPAL_FIELD("work.", LightPassWork, first),
    OPAL_FIELD("work.", LightPassWork, count),
    OPAL_FIELD("work.", LightPassWork, layer),
    OPAL_FIELD("work.", LightPassWork, resumed),
    OPAL_FIELD("work.", LightPassWork, piece),
    OPAL_FIELD("work.", LightPassWork, last),
    OPAL_FIELD("work.", LightPassWork, slotFirst),
    OPAL_FIELD("marchWork.", MarchWork, origin),
    OPAL_FIELD("marchWork.", MarchWork, mode),
    OPAL_FIELD("marchWork.", MarchWork, first),
    OPAL_FIELD("marchWork.", MarchWork, count),
    OPAL_FIELD("marchWork.", MarchWork, subRay),
    OPAL_FIELD("marchWork.", MarchWork, piece),
    OPAL_FIELD("marchWork.", MarchWork, resumed),
    OPAL_FIELD("marchWork.", MarchWork, last),
    OPAL_FIELD("marchWork.", MarchWork, sharesRays),
    OPAL_FIELD("pixelSums[0].", PixelSum, xyz),
    OPAL_FIELD("pixelSums[0].", PixelSum, depth),
    OPAL_FIELD("pixelSums[0].", PixelSum, dominantLambda),
    OPAL_FIELD("pixelSums[0].", PixelSum, dominantY),
    OPAL_FIELD("pixelSums[0].", PixelSum, dominantDomain),
    OPAL_FIELD("pixelSums[0].", PixelSum, hits),
    OPAL_FIELD("pixelSums[0].", PixelSum, firstDomainSeen),
    OPAL_FIELD("pixelSums[0].", PixelSum, brightestDomainSeen),
    OPAL_FIELD("pixelSums[0].", PixelSum, alike),
    OPAL_FIELD("highlightWork.", HighlightWork, first),
    OPAL_FIELD("highlightWork.", HighlightWork, count),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, voxelCells),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, surfaceDistance),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, lightField),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, lightAbsorption),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, absorptionCells),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, lightShadow),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, entryVoxels),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, scatteredLight),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, scatteredLightGrid),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, surfaceTiles),
    OPAL_FIELD("volumeAddresses.", VolumeAddresses, surfaceTileValues),
    OPAL_FIELD("surfaceTiles[0].", SurfaceTile, slot),
    OPAL_FIELD("surfaceTiles[0].", SurfaceTile, bound),
  };
#undef OPAL_FIELD
  return table;
}

// Prefixes of the contract's structs in the shaders' reflection.
const std::set<std::string> contractPrefixes = { "P.", "bins[0].", "queues[0].", "lightField[0].", "lightAbsorption[0].", "lightShadow[0].", "scatteredLightNodes[0].", "domains[0].", "pixelColour[0].",
  "pixelBragg[0].", "pixelMirror[0].", "pixelSums[0].", "work.", "marchWork.", "highlightWork.", "volumeAddresses.", "surfaceTiles[0]." };

// Array strides the reflection reports for the contract's records.
const std::map<std::string, std::size_t> expectedStrides = { { "bins[0].", sizeof(WavelengthBinRecord) },
  { "lightField[0].", sizeof(LightFieldPair) }, { "lightAbsorption[0].", sizeof(LightFieldPair) }, { "lightShadow[0].", sizeof(LightShadow) }, { "scatteredLightNodes[0].", sizeof(ScatteredLightNode) }, { "queues[0].", sizeof(DispatchQueue) }, { "domains[0].", sizeof(DomainRecord) }, { "pixelColour[0].", sizeof(PixelColour) },
  { "pixelBragg[0].", sizeof(PixelBragg) }, { "pixelMirror[0].", sizeof(PixelMirror) },
  { "pixelSums[0].", sizeof(PixelSum) }, { "surfaceTiles[0].", sizeof(SurfaceTile) } };

// The reflection of a pass as built: `options` "" or, for the passes that
// read per-voxel fields by address, "--target-env vulkan1.2 -DOPAL_VOLUME_ADDRESSES".
std::string reflect(
  const std::string& validator, const std::string& shaderDir, const std::string& shader, const std::string& options)
{
  const std::string command = validator + " -V -q --reflect-all-block-variables " +
    (options.empty() ? std::string("--target-env vulkan1.1") : options) + " -I" + shaderDir + " -o /dev/null " +
    shaderDir + "/" + shader + " 2>&1";
  std::string output;
  if (FILE* pipe = ::popen(command.c_str(), "r"))
  {
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe))
    {
      output += buffer;
    }
    OPAL_CHECK(::pclose(pipe) == 0, shader + " compiles: " + output);
  }
  return output;
}

std::string prefixOf(const std::string& name)
{
  for (const std::string& prefix : contractPrefixes)
  {
    if (name.compare(0, prefix.size(), prefix) == 0)
    {
      return prefix;
    }
  }
  return {};
}

// A member line of glslang's reflection, "NAME: offset N, ..." with
// "topLevelArrayStride S" at its end for an array; nullopt for other lines.
struct ReflectedMember
{
  std::string Name;
  std::size_t Offset = 0;
  std::optional<std::size_t> Stride;
};

bool allOf(const std::string& text, bool (*test)(char))
{
  return !text.empty() && std::all_of(text.begin(), text.end(), test);
}

bool digit(char c)
{
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

std::optional<ReflectedMember> reflectedMember(const std::string& line)
{
  const std::string offsetKey = ": offset ", strideKey = "topLevelArrayStride ";
  const std::size_t colon = line.find(offsetKey);
  const auto nameChar = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || (c != '\0' && std::strchr("_[].", c) != nullptr);
  };
  if (colon == std::string::npos || !allOf(line.substr(0, colon), +nameChar))
  {
    return std::nullopt;
  }
  const std::size_t first = colon + offsetKey.size(), comma = line.find(',', first);
  if (comma == std::string::npos || !allOf(line.substr(first, comma - first), digit))
  {
    return std::nullopt;
  }
  ReflectedMember member{ line.substr(0, colon), std::stoul(line.substr(first, comma - first)), std::nullopt };
  const std::size_t stride = line.rfind(strideKey);
  if (stride != std::string::npos && stride > comma && allOf(line.substr(stride + strideKey.size()), digit))
  {
    member.Stride = std::stoul(line.substr(stride + strideKey.size()));
  }
  return member;
}

// The size glslang reflects for the parameter block
// ("ParameterBlock: offset -1, type HEX, size N,"), where the shader declares it.
std::optional<std::size_t> parameterBlockSize(const std::string& reflection)
{
  const std::string key = "ParameterBlock: offset -1, type ", sizeKey = ", size ";
  for (std::size_t at = reflection.find(key); at != std::string::npos; at = reflection.find(key, at + 1))
  {
    const std::size_t type = at + key.size(), size = reflection.find(sizeKey, type);
    const std::size_t comma = size == std::string::npos ? size : reflection.find(',', size + sizeKey.size());
    const auto hex = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0 || (c >= 'a' && c <= 'f'); };
    if (comma != std::string::npos && allOf(reflection.substr(type, size - type), +hex) &&
      allOf(reflection.substr(size + sizeKey.size(), comma - size - sizeKey.size()), digit))
    {
      return std::stoul(reflection.substr(size + sizeKey.size(), comma - size - sizeKey.size()));
    }
  }
  return std::nullopt;
}

// Checks each reflected contract member of one shader; returns the names seen.
std::set<std::string> checkShader(const std::string& shader, const std::string& reflection)
{
  std::set<std::string> seen;
  std::istringstream lines(reflection);
  std::string text;
  while (std::getline(lines, text))
  {
    const std::optional<ReflectedMember> member = reflectedMember(text);
    if (!member)
    {
      continue;
    }
    const std::string& name = member->Name;
    // The march's vec4 views of the light fields (LightFieldPairAsVec4): one
    // element a LightFieldPair.
    if ((name == "lightField" || name == "lightAbsorption") && member->Offset == 0 && member->Stride)
    {
      OPAL_CHECK(*member->Stride == sizeof(LightFieldPair), shader + ": the vec4 view " + name + " has stride " +
          std::to_string(*member->Stride) + " = sizeof(LightFieldPair) " + std::to_string(sizeof(LightFieldPair)));
      seen.insert(name + " as vec4");
    }
    if (prefixOf(name).empty())
    {
      continue; // not a member of the contract's structs
    }
    const auto expected = expectedOffsets().find(name);
    OPAL_CHECK(expected != expectedOffsets().end(), shader + ": " + name + " is checked by this test's table");
    if (expected != expectedOffsets().end())
    {
      OPAL_CHECK(member->Offset == expected->second, shader + ": " + name + " at GLSL offset " +
          std::to_string(member->Offset) + ", C++ offset " + std::to_string(expected->second));
    }
    const auto stride = expectedStrides.find(prefixOf(name));
    if (member->Stride && stride != expectedStrides.end())
    {
      OPAL_CHECK(*member->Stride == stride->second, shader + ": " + name + " array stride " +
          std::to_string(*member->Stride) + " = sizeof " + std::to_string(stride->second));
    }
    seen.insert(name);
  }
  if (const std::optional<std::size_t> size = parameterBlockSize(reflection))
  {
    OPAL_CHECK(*size == sizeof(RenderParameterBlock), shader + ": the parameter block's size " +
        std::to_string(*size) + " = sizeof " + std::to_string(sizeof(RenderParameterBlock)));
  }
  return seen;
}
} // namespace

int TestOpalShaderContract(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestOpalShaderContract GLSLANG_VALIDATOR SHADER_DIR" << std::endl;
    return 2;
  }
  std::set<std::string> seen;
  const std::string addressed = "--target-env vulkan1.2 -DOPAL_VOLUME_ADDRESSES";
  for (const auto& [shader, options] : std::vector<std::pair<std::string, std::string>>{ { "light_optical_depth.comp", "" },
         { "view_march.comp", "" }, { "specular_highlight.comp", "" }, { "spectrum_to_colour.comp", "" },
         { "bragg_shadow_table.comp", "" }, { "light_optical_depth.comp", addressed }, { "view_march.comp", addressed },
         { "specular_highlight.comp", addressed } })
  {
    const std::set<std::string> names = checkShader(shader, reflect(argv[1], argv[2], shader, options));
    seen.insert(names.begin(), names.end());
  }
  for (const auto& [name, offset] : expectedOffsets())
  {
    OPAL_CHECK(seen.count(name) == 1, name + " is declared by some pass and so compared");
  }
  for (const char* view : { "lightField as vec4", "lightAbsorption as vec4" })
  {
    OPAL_CHECK(seen.count(view) == 1, std::string("the march's ") + view + " is compared");
  }
  return opaltest::finish("TestOpalShaderContract");
}
