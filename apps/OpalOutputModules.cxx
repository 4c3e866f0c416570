#include "OpalOutputModules.h"

#include "OpalAtomicFile.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>

namespace opal
{

namespace
{
// Loads ../lib/FILE relative to the running program and returns the table
// its ENTRY function gives. The module stays loaded for the process's life.
template <typename Table>
const Table& loadModule(const char* file, const char* entry)
{
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path path = program.parent_path().parent_path() / "lib" / file;
  void* library = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library)
  {
    const char* reason = ::dlerror();
    throw std::runtime_error("cannot load " + path.string() + ": " + (reason ? reason : "unknown reason"));
  }
  auto* function = reinterpret_cast<const Table* (*)()>(::dlsym(library, entry));
  if (!function)
  {
    throw std::runtime_error(path.string() + " lacks " + entry);
  }
  return *function();
}
} // namespace

const ImageOutputModule& imageOutputModule(const std::string& path)
{
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".png")
  {
    static const ImageOutputModule& png = loadModule<ImageOutputModule>(OPAL_PNG_OUTPUT_MODULE, "opalPngOutputModule");
    return png;
  }
  if (extension == ".jpg" || extension == ".jpeg")
  {
    static const ImageOutputModule& jpeg =
      loadModule<ImageOutputModule>(OPAL_JPEG_OUTPUT_MODULE, "opalJpegOutputModule");
    return jpeg;
  }
  static const ImageOutputModule& module =
    loadModule<ImageOutputModule>(OPAL_IMAGE_OUTPUT_MODULE, "opalImageOutputModule");
  return module;
}

const VtiOutputModule& vtiOutputModule()
{
  static const VtiOutputModule& module = loadModule<VtiOutputModule>(OPAL_VTI_OUTPUT_MODULE, "opalVtiOutputModule");
  return module;
}

} // namespace opal
