#include "OpalRenderCamera.h"

#include "OpalRotation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace opal
{

namespace
{
glm::dvec3 vec(const std::array<double, 3>& a)
{
  return { a[0], a[1], a[2] };
}

// R^-1 for the stone's rotation: the preset's placement, then ModelRotation.
glm::dmat3 toModelFrame(const RenderParameters& p)
{
  return glm::transpose(rotationOfDegrees(p.ModelRotation) * rotationOfDegrees(p.PresetRotation));
}
} // namespace

RenderCamera cameraInModelFrame(const RenderParameters& p)
{
  const glm::dmat3 toModel = toModelFrame(p);
  RenderCamera camera;
  camera.Eye = toModel * vec(p.EyePosition);
  camera.Light = toModel * vec(p.LightPosition);
  camera.Forward = glm::normalize(toModel * (vec(p.FocalPoint) - vec(p.EyePosition)));
  const glm::dvec3 right = glm::cross(camera.Forward, toModel * vec(p.ViewUp));
  if (glm::length(right) < 1e-9)
  {
    throw std::invalid_argument("ViewUp must not be parallel to the view direction.");
  }
  camera.Right = glm::normalize(right);
  camera.Up = glm::cross(camera.Right, camera.Forward);
  return camera;
}

std::array<int, 4> renderedRegion(const RenderParameters& p)
{
  return { p.ImageRegion[0], p.ImageRegion[1],
    p.ImageRegion[2] > 0 ? p.ImageRegion[2] : p.ImageSize[0] - p.ImageRegion[0],
    p.ImageRegion[3] > 0 ? p.ImageRegion[3] : p.ImageSize[1] - p.ImageRegion[1] };
}

std::array<int, 2> exposureThumbnailSize(const RenderParameters& p)
{
  const double scale = std::min(1.0, 96.0 / std::max(p.ImageSize[0], p.ImageSize[1]));
  return { std::max(1, static_cast<int>(std::lround(p.ImageSize[0] * scale))),
    std::max(1, static_cast<int>(std::lround(p.ImageSize[1] * scale))) };
}

} // namespace opal
