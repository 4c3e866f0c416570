// A frame's view and light in the model's frame (docs/design.md §3), and the
// image rectangles a frame renders. Rotating the model by R is seeing the
// unrotated model with everything else turned by R^-1, so the volume never
// moves and the camera and the light do.
#pragma once

#include "OpalRenderParameters.h"

#include <glm/glm.hpp>

#include <array>

namespace opal
{

struct RenderCamera
{
  glm::dvec3 Eye{};
  glm::dvec3 Forward{}; // unit view direction
  glm::dvec3 Right{};   // unit image x
  glm::dvec3 Up{};      // unit image y
  glm::dvec3 Light{};
};

// Throws std::invalid_argument if ViewUp is parallel to the view direction.
RenderCamera cameraInModelFrame(const RenderParameters& parameters);

// The rectangle of the image the parameters ask for: x0, y0, width, height.
std::array<int, 4> renderedRegion(const RenderParameters& parameters);

// The automatic exposure's thumbnail of the whole image: at most 96 pixels
// across, the image's aspect.
std::array<int, 2> exposureThumbnailSize(const RenderParameters& parameters);

} // namespace opal
