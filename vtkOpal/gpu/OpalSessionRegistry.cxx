#include "OpalSessionRegistry.h"

#include "OpalRenderSession.h"

#include <cstdlib>
#include <mutex>
#include <set>

namespace opal
{
namespace sessionregistry
{
namespace
{
// Never destroyed (deliberately): sessions outlive static destruction.
std::mutex& lock()
{
  static auto* mutex = new std::mutex;
  return *mutex;
}

std::set<RenderSession*>& sessions()
{
  static auto* live = new std::set<RenderSession*>;
  return *live;
}

void releaseAll()
{
  std::lock_guard<std::mutex> guard(lock());
  for (RenderSession* session : sessions())
  {
    session->release();
  }
}
} // namespace

void add(RenderSession* session)
{
  std::lock_guard<std::mutex> guard(lock());
  sessions().insert(session);
  static const bool registered = std::atexit(&releaseAll) == 0;
  (void)registered;
}

void remove(RenderSession* session)
{
  std::lock_guard<std::mutex> guard(lock());
  sessions().erase(session);
}
} // namespace sessionregistry
} // namespace opal
