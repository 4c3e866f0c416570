#include "OpalAtomicFile.h"

#include <algorithm>
#include <cctype>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace
{
// Longest file name most file systems take (NAME_MAX).
constexpr std::size_t MaxNameBytes = 255;

// A hidden name beside path with `tag` and `ending`, shortened to a fixed
// form where the target's own name is near the length limit.
std::filesystem::path besideName(const std::filesystem::path& path, const std::string& tag, const std::string& ending)
{
  const std::string pid = std::to_string(::getpid());
  std::string name = "." + path.stem().string() + "." + tag + "-" + pid + ending;
  if (name.size() > MaxNameBytes)
  {
    name = ".opal-" + tag + "-" + pid + ending;
  }
  std::filesystem::path beside = path;
  beside.replace_filename(name);
  return beside;
}

// A name beside path for its earlier contents.
std::filesystem::path backupName(const std::filesystem::path& path)
{
  return besideName(path, "earlier", path.extension().string());
}

// The bytes a complete file of this extension ends with (PNG's IEND chunk,
// JPEG's end-of-image marker, VTK XML's closing tag before its newline), or
// none for formats whose writer reports a short write itself (EXR, TIFF).
std::string expectedEnding(const std::filesystem::path& path)
{
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".png")
  {
    return std::string("\0\0\0\0IEND\xAE\x42\x60\x82", 12);
  }
  if (extension == ".jpg" || extension == ".jpeg")
  {
    return "\xFF\xD9";
  }
  return extension == ".vti" ? "</VTKFile>" : "";
}

// Whether the file was written whole and reached the disk: flushed (fsync
// reports a full disk that buffered writes hid) and ending as its format
// must. Writers (libpng, VTK's XML writer) report success for a file cut
// short by a full disk or a file-size limit.
bool writtenWhole(const std::filesystem::path& file)
{
  const int descriptor = ::open(file.c_str(), O_RDONLY);
  const bool flushed = descriptor >= 0 && ::fsync(descriptor) == 0;
  if (descriptor >= 0)
  {
    ::close(descriptor);
  }
  std::string ending = expectedEnding(file);
  if (!flushed || ending.empty())
  {
    return flushed;
  }
  std::ifstream stream(file, std::ios::binary);
  std::string tail(ending.size() + 2, '\0');
  stream.seekg(-static_cast<std::streamoff>(tail.size()), std::ios::end);
  stream.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  return stream.gcount() == static_cast<std::streamsize>(tail.size()) && tail.find(ending) != std::string::npos;
}

// Where a path leads with every symbolic link followed, even one to a file
// not yet written (which weakly_canonical leaves as the link's own name).
std::filesystem::path followedPath(const std::filesystem::path& path)
{
  std::error_code ignored; // a step that fails leaves the path as far as it got
  std::filesystem::path current = std::filesystem::absolute(path, ignored);
  // 40 links at most, as the kernel follows (ELOOP beyond).
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(current, ignored); ++hop)
  {
    // A relative link is relative to the folder the link is in.
    const std::filesystem::path link = std::filesystem::read_symlink(current, ignored);
    current = std::filesystem::weakly_canonical(current.parent_path(), ignored) / link;
  }
  std::error_code error;
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(current, error);
  return error ? current.lexically_normal() : resolved;
}

// Whether two paths name one file: the same device and inode where both
// exist (hard links too), else the same path once links are followed.
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b)
{
  struct stat first = {}, second = {};
  if (::stat(a.c_str(), &first) == 0 && ::stat(b.c_str(), &second) == 0)
  {
    return first.st_dev == second.st_dev && first.st_ino == second.st_ino;
  }
  return followedPath(a) == followedPath(b);
}
} // namespace

std::string lowerCaseExtension(const std::filesystem::path& path)
{
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

std::filesystem::path resolvedTarget(const std::filesystem::path& path)
{
  std::error_code error;
  const std::filesystem::path resolved =
    std::filesystem::is_symlink(path, error) ? std::filesystem::weakly_canonical(path, error) : path;
  return error ? path : resolved;
}

std::string sharedFileError(const std::vector<OutputName>& outputs)
{
  for (std::size_t i = 0; i < outputs.size(); ++i)
  {
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
    {
      if (sameFile(outputs[i].Path, outputs[j].Path))
      {
        return outputs[i].Flag + " " + outputs[i].Path + " and " + outputs[j].Flag + " " + outputs[j].Path +
          " are one file; give each output a file of its own";
      }
    }
  }
  return {};
}

std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write)
{
  // As cp does: through a symbolic link to the file it names, keeping an
  // existing file's permissions, and refusing one we may not write.
  const std::filesystem::path target = resolvedTarget(path);
  std::error_code error;
  const bool exists = std::filesystem::exists(target, error);
  if (exists && ::access(target.c_str(), W_OK) != 0)
  {
    return "could not write " + path.string() + ": permission denied";
  }
  // Keep the extension last: writers pick the format from it.
  const std::filesystem::path temporary = besideName(target, "partial", target.extension().string());
  if (!write(temporary.string()) || !writtenWhole(temporary))
  {
    std::filesystem::remove(temporary, error);
    return "could not write " + path.string() + " (the disk is full, or the file would be too large)";
  }
  if (exists)
  {
    std::filesystem::permissions(temporary, std::filesystem::status(target, error).permissions(), error);
  }
  std::filesystem::rename(temporary, target, error);
  if (error)
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "could not move the finished file to " + path.string() + ": " + error.message();
  }
  return {};
}

FileSetTransaction::FileSetTransaction(const std::vector<std::filesystem::path>& targets)
{
  for (const std::filesystem::path& named : targets)
  {
    const std::filesystem::path path = resolvedTarget(named); // written through links, as cp does
    Target target{ path, {} };
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error))
    {
      target.Backup = backupName(path);
      std::filesystem::create_hard_link(path, target.Backup, error);
      if (error)
      {
        error.clear();
        std::filesystem::copy_file(path, target.Backup, std::filesystem::copy_options::overwrite_existing, error);
      }
      if (error)
      {
        // No room for a copy (a full disk): the earlier file cannot be kept aside.
        std::error_code ignored;
        std::filesystem::remove(target.Backup, ignored);
        target.Backup.clear();
      }
    }
    this->Targets.push_back(target);
  }
}

void FileSetTransaction::commit()
{
  this->Committed = true;
}

FileSetTransaction::~FileSetTransaction()
{
  for (const Target& target : this->Targets)
  {
    std::error_code ignored;
    if (this->Committed)
    {
      std::filesystem::remove(target.Backup, ignored);
    }
    else if (!target.Backup.empty())
    {
      // Renaming a hard link onto another link of the same file does nothing
      // (POSIX): where the target was never replaced, drop the link.
      if (std::filesystem::equivalent(target.Backup, target.Path, ignored))
      {
        std::filesystem::remove(target.Backup, ignored);
      }
      else
      {
        std::filesystem::rename(target.Backup, target.Path, ignored);
      }
    }
    else
    {
      std::filesystem::remove(target.Path, ignored);
    }
  }
}

SignalsHeld::SignalsHeld()
{
  sigset_t ending;
  sigemptyset(&ending);
  for (int signal : { SIGINT, SIGTERM, SIGHUP, SIGQUIT })
  {
    sigaddset(&ending, signal);
  }
  sigprocmask(SIG_BLOCK, &ending, &this->Previous);
}

SignalsHeld::~SignalsHeld()
{
  sigprocmask(SIG_SETMASK, &this->Previous, nullptr);
}
