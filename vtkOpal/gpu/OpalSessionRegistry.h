// Every live render session, so that the process's exit ends their device
// objects before the Vulkan layers and driver tear down their own state
// (docs/design.md §5): ParaView deletes its filters only in its libraries'
// static destruction, after the validation layer's, and destroying the
// buffers then crashed in it. Internal to OpalGpu.
#pragma once

namespace opal
{
class RenderSession;

namespace sessionregistry
{
// Registers a session; the first one also registers the exit handler, after
// the Vulkan libraries it loaded registered theirs, so it runs before them.
void add(RenderSession* session);
void remove(RenderSession* session);
} // namespace sessionregistry
} // namespace opal
