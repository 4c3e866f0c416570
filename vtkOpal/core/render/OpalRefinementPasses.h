// The frames a live view held still renders after its preview, coarse to fine
// (docs/design.md §5.2). Plain data.
#pragma once

#include "OpalRenderParameters.h"

#include <vector>

namespace opal
{

// Previews at PreviewScale 4, then 2, each only where finer than the preview
// drawn (they keep that preview's light: no light pass), then the final
// frame, which is the still render's frame exactly.
std::vector<RenderParameters> refinementPasses(const RenderParameters& drawnPreview, const RenderParameters& finalFrame);

} // namespace opal
