#include "OpalAtomicFile.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fcntl.h>
#include <random>
#include <sys/resource.h>
#include <sys/sendfile.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <system_error>
#include <unistd.h>

namespace
{
// Longest file name most file systems take (NAME_MAX).
constexpr std::size_t MaxNameBytes = 255;

// Twelve letters or digits (71 bits) from the system's random source: a name
// no one can plant a link or a file under in advance.
std::string unpredictableTag()
{
  static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device source;
  std::uniform_int_distribution<std::size_t> pick(0, sizeof(letters) - 2);
  std::string tag(12, ' ');
  for (char& letter : tag)
  {
    letter = letters[pick(source)];
  }
  return tag;
}

// A fresh hidden name beside path, ".NAME.KIND-RANDOM.EXT" (the extension
// last, as people and tools read the format from it), shortened to a fixed
// form where the target's own name is near the length limit.
std::filesystem::path besideName(const std::filesystem::path& path, const std::string& kind)
{
  const std::string unique = kind + "-" + unpredictableTag() + path.extension().string();
  std::string name = "." + path.stem().string() + "." + unique;
  if (name.size() > MaxNameBytes)
  {
    name = ".opal-" + unique;
  }
  std::filesystem::path beside = path;
  beside.replace_filename(name);
  return beside;
}

// Calls claim(name) with fresh names beside path until it succeeds (returns
// 0) or fails for a reason other than the name being taken (returns errno);
// a name already taken, by whatever, is left as it is. Returns the name
// claimed, or an empty path with `failure` set.
std::filesystem::path claimBesideName(const std::filesystem::path& path, const std::string& kind,
  const std::function<int(const std::filesystem::path&)>& claim, int& failure)
{
  failure = EEXIST;
  for (int attempt = 0; attempt < 16 && failure == EEXIST; ++attempt)
  {
    const std::filesystem::path name = besideName(path, kind);
    failure = claim(name);
    if (failure == 0)
    {
      return name;
    }
  }
  return {};
}

// An open file descriptor, closed when this ends.
struct Descriptor
{
  int Number = -1;
  Descriptor() = default;
  explicit Descriptor(int number)
    : Number(number)
  {
  }
  ~Descriptor()
  {
    if (this->Number >= 0)
    {
      ::close(this->Number);
    }
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
};

// A file this process created beside a target with O_EXCL, so never a link
// or a file that was already there; removed when this ends unless kept.
class OwnedFile
{
public:
  OwnedFile(const std::filesystem::path& target, const std::string& kind, mode_t mode)
  {
    this->Path = claimBesideName(
      target, kind,
      [&](const std::filesystem::path& name) {
        this->Open.Number = ::open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, mode);
        return this->Open.Number >= 0 ? 0 : errno;
      },
      this->Failure);
  }
  ~OwnedFile()
  {
    if (!this->Kept && !this->Path.empty())
    {
      ::unlink(this->Path.c_str());
    }
  }
  OwnedFile(const OwnedFile&) = delete;
  OwnedFile& operator=(const OwnedFile&) = delete;

  int descriptor() const { return this->Open.Number; }
  const std::filesystem::path& path() const { return this->Path; }
  // The errno of the creation, where descriptor() < 0.
  int failure() const { return this->Failure; }
  // A name that opens this very file, whatever becomes of its name meanwhile.
  std::string openName() const { return "/proc/self/fd/" + std::to_string(this->Open.Number); }
  void keep() { this->Kept = true; }

private:
  std::filesystem::path Path;
  Descriptor Open;
  int Failure = 0;
  bool Kept = false;
};

// The folder a file goes in, as its path names it.
std::filesystem::path folderOf(const std::filesystem::path& file)
{
  return file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
}

// Why no file can be made in the target's folder, or empty. Said before a
// writer tries, whose own message ("Write Error") would not tell.
std::string folderProblem(const std::filesystem::path& target)
{
  struct stat status = {};
  const int error = ::stat(folderOf(target).c_str(), &status) == 0 ? 0 : errno;
  const std::string folder = "its folder " + folderOf(target).string();
  if (error == 0)
  {
    return S_ISDIR(status.st_mode) ? "" : folder + " is not a folder";
  }
  switch (error)
  {
    case ENOENT:
      return folder + " does not exist";
    case ENOTDIR:
      return folder + " cannot exist: a part of its path is a file";
    case EACCES:
      return folder + " cannot be reached: permission denied";
    default:
      return folder + ": " + std::generic_category().message(error);
  }
}

// The file-size limit (ulimit -f) in bytes, RLIM_INFINITY where none is set.
rlim_t fileSizeLimit()
{
  struct rlimit limit = {};
  return ::getrlimit(RLIMIT_FSIZE, &limit) == 0 ? limit.rlim_cur : RLIM_INFINITY;
}

// Why a file could not be written past the file-size limit, with the limit.
std::string tooLarge()
{
  const rlim_t limit = fileSizeLimit();
  return "the file would be larger than the file-size limit" +
    (limit == RLIM_INFINITY ? std::string() : " of " + std::to_string(limit) + " bytes");
}

// What an errno of creating or writing a file means for the user (the
// default: one of creating it).
std::string causeOf(int error, const std::filesystem::path& target)
{
  switch (error)
  {
    case ENOSPC:
      return "the disk is full";
    case EDQUOT:
      return "the disk quota is used up";
    case EFBIG:
      return tooLarge();
    case EACCES:
    case EPERM:
      return "permission denied in its folder " + folderOf(target).string();
    case EROFS:
      return "its folder " + folderOf(target).string() + " is on a read-only file system";
    case EIO:
      return "the disk reported an input/output error";
    default:
      return "no file can be made in its folder " + folderOf(target).string() + " (" +
        std::generic_category().message(error) + ")";
  }
}

// Why a writer failed or cut its file short, or empty if unknown. Writers
// lose errno in their clean-up, so the file-size limit and the free space
// are looked at first.
std::string writeFailureCause(int descriptor, int writerError, const std::filesystem::path& target)
{
  struct stat status = {};
  const rlim_t limit = fileSizeLimit();
  if (::fstat(descriptor, &status) == 0 && limit != RLIM_INFINITY && static_cast<rlim_t>(status.st_size) >= limit)
  {
    return tooLarge();
  }
  struct statvfs space = {};
  if (::fstatvfs(descriptor, &space) == 0 && space.f_bavail == 0)
  {
    return "the disk is full";
  }
  const bool telling = writerError == ENOSPC || writerError == EDQUOT || writerError == EFBIG || writerError == EIO;
  return telling ? causeOf(writerError, target) : "";
}

// The bytes a complete file of this extension ends with (PNG's IEND chunk,
// JPEG's end-of-image marker, VTK XML's closing tag before its newline), or
// none for formats checked otherwise (EXR's writer reports a short write, a
// TIFF is read back).
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

// Whether the open file ends as a complete file of its format must (the
// ending within its last bytes). Writers (libpng, VTK's XML writer) report
// success for a file cut short by a full disk or a file-size limit.
bool endsWhole(int descriptor, const std::string& ending)
{
  struct stat status = {};
  const auto span = static_cast<off_t>(ending.size() + 2);
  if (ending.empty() || ::fstat(descriptor, &status) != 0 || status.st_size < span)
  {
    return ending.empty();
  }
  std::string tail(static_cast<std::size_t>(span), '\0');
  return ::pread(descriptor, tail.data(), tail.size(), status.st_size - span) == span &&
    tail.find(ending) != std::string::npos;
}

// Runs the writer on the file and checks that what it wrote reached the disk
// whole (fsync reports a full disk that buffered writes hid); empty on
// success, else the cause.
std::string writeWhole(
  const OwnedFile& file, const std::function<bool(const std::string&)>& write, const std::filesystem::path& target)
{
  std::string thrown;
  bool written = false;
  errno = 0;
  try
  {
    written = write(file.openName());
  }
  catch (const std::exception& exception)
  {
    thrown = exception.what();
  }
  int error = errno;
  if (written && ::fsync(file.descriptor()) != 0)
  {
    written = false;
    error = errno;
  }
  if (written && endsWhole(file.descriptor(), expectedEnding(target)))
  {
    return {};
  }
  const std::string cause = writeFailureCause(file.descriptor(), error, target);
  const std::string fallback = !thrown.empty() ? thrown : written ? "the file was cut short" : "the writer failed";
  return cause.empty() ? fallback : cause;
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

// Keeps path's contents aside under an unpredictable name: a hard link
// (instant, no space), else a copy where the file system has none. Empty
// where neither can be made (a full disk): the earlier file cannot be kept.
std::filesystem::path keepAside(const std::filesystem::path& path)
{
  int failure = 0;
  const std::filesystem::path link = claimBesideName(
    path, "earlier",
    [&](const std::filesystem::path& name) { return ::link(path.c_str(), name.c_str()) == 0 ? 0 : errno; }, failure);
  if (!link.empty())
  {
    return link;
  }
  const Descriptor source(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  struct stat status = {};
  if (source.Number < 0 || ::fstat(source.Number, &status) != 0)
  {
    return {};
  }
  OwnedFile copy(path, "earlier", 0600);
  off_t left = copy.descriptor() >= 0 ? status.st_size : -1;
  while (left > 0)
  {
    const ssize_t sent = ::sendfile(copy.descriptor(), source.Number, nullptr, static_cast<std::size_t>(left));
    left = sent > 0 ? left - sent : -1;
  }
  if (left != 0 || ::fchmod(copy.descriptor(), status.st_mode & 07777) != 0)
  {
    return {};
  }
  copy.keep();
  return copy.path();
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

namespace
{
// Where a file written to `path` goes, as cp writes: through a symbolic link
// to the file it names, keeping an existing file's permissions, and refusing
// one we may not write.
struct Destination
{
  std::filesystem::path Target;
  bool Exists = false;
  struct stat Existing = {};
  std::string Problem; // why nothing can be written there, or empty
};

Destination destinationOf(const std::filesystem::path& path)
{
  Destination destination;
  destination.Target = resolvedTarget(path);
  destination.Problem = folderProblem(destination.Target);
  destination.Exists = ::stat(destination.Target.c_str(), &destination.Existing) == 0;
  if (destination.Problem.empty() && destination.Exists && ::access(destination.Target.c_str(), W_OK) != 0)
  {
    destination.Problem = "permission denied";
  }
  return destination;
}
} // namespace

std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write)
{
  const std::string failed = "could not write " + path.string() + ": ";
  const Destination destination = destinationOf(path);
  if (!destination.Problem.empty())
  {
    return failed + destination.Problem;
  }
  const std::filesystem::path& target = destination.Target;
  const bool exists = destination.Exists;
  const struct stat& existing = destination.Existing;
  // Private while written where it replaces a file, whose permissions it
  // takes at the end; else those the umask gives a new file.
  OwnedFile temporary(target, "partial", exists ? 0600 : 0666);
  if (temporary.descriptor() < 0)
  {
    return failed + causeOf(temporary.failure(), target);
  }
  if (const std::string cause = writeWhole(temporary, write, target); !cause.empty())
  {
    return failed + cause;
  }
  if (exists)
  {
    ::fchmod(temporary.descriptor(), existing.st_mode & 07777);
  }
  std::error_code error;
  std::filesystem::rename(temporary.path(), target, error);
  if (error)
  {
    return "could not move the finished file to " + path.string() + ": " + error.message();
  }
  temporary.keep();
  return {};
}

std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&, std::string&)>& write)
{
  std::string reason;
  const std::string error = writeFileAtomically(path, [&](const std::string& file) { return write(file, reason); });
  return error.empty() || reason.empty() ? error : error + " (" + reason + ")";
}

std::string moveFileAtomically(const std::filesystem::path& finished, const std::filesystem::path& path)
{
  const std::string failed = "could not write " + path.string() + ": ";
  const Destination destination = destinationOf(path);
  if (!destination.Problem.empty())
  {
    return failed + destination.Problem;
  }
  const Descriptor file(::open(finished.c_str(), O_RDONLY | O_CLOEXEC));
  if (file.Number < 0)
  {
    return failed + "the finished file " + finished.string() + " cannot be opened";
  }
  errno = 0;
  if (::fsync(file.Number) != 0 || !endsWhole(file.Number, expectedEnding(destination.Target)))
  {
    const std::string cause = writeFailureCause(file.Number, errno, destination.Target);
    return failed + (cause.empty() ? "the file was cut short" : cause);
  }
  if (destination.Exists)
  {
    ::fchmod(file.Number, destination.Existing.st_mode & 07777);
  }
  std::error_code error;
  std::filesystem::rename(finished, destination.Target, error);
  if (error.value() == EXDEV) // a link to another file system: copied there
  {
    return writeFileAtomically(path, [&](const std::string& copy) {
      std::filesystem::copy_file(finished, copy, std::filesystem::copy_options::overwrite_existing);
      return true;
    });
  }
  return error ? "could not move the finished file to " + path.string() + ": " + error.message() : std::string();
}

FileSetTransaction::FileSetTransaction(const std::vector<std::filesystem::path>& targets)
{
  for (const std::filesystem::path& named : targets)
  {
    const std::filesystem::path path = resolvedTarget(named); // written through links, as cp does
    std::error_code error;
    const bool existed = std::filesystem::exists(std::filesystem::symlink_status(path, error));
    const bool regular = std::filesystem::is_regular_file(path, error);
    this->Targets.push_back({ path, regular ? keepAside(path) : std::filesystem::path(), existed });
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
    else if (!target.Existed)
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
