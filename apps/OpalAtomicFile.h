// Writes a file under a temporary name in the same folder and renames it into
// place, so an earlier file is never replaced by a partial one; and a set of
// files replaced all or none. The temporary files and the earlier contents
// kept aside get unpredictable names, created exclusively: nothing planted in
// a shared folder is written through or deleted.
#pragma once

#include <csignal>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

// The path's extension in lower case (".png"), which names its format.
std::string lowerCaseExtension(const std::filesystem::path& path);

// The file a path names: a symbolic link's target, the path itself otherwise.
std::filesystem::path resolvedTarget(const std::filesystem::path& path);

// One output of a run: the flag that named it and its path.
struct OutputName
{
  std::string Flag, Path;
};

// Empty when every output names a file of its own; else one line naming the
// first two that resolve to one file (the same name, ./x and x, a symbolic
// link to it, even one to a file not yet written, or a hard link): the run
// would write that file twice, and a later failed write would delete it.
std::string sharedFileError(const std::vector<OutputName>& outputs);

// Calls write(file) and, on success, renames what it wrote to path: to the
// file a symbolic link there names, keeping an existing file's permissions,
// and refusing one this process may not write, as cp does. `file` opens a
// file this call created exclusively under an unpredictable name beside the
// target (through /proc/self/fd, so a link planted under that name cannot
// redirect the writer); writers take the format from path, not from it.
// Returns an empty string on success, else "could not write PATH: " and the
// cause (the folder, the disk, the file-size limit); the temporary file never
// survives. A writer's exception is such a failure, not the caller's.
std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write);

// The same for writers that say why they failed (write(file, reason)): the
// reason follows the cause in brackets.
std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&, std::string&)>& write);

// The same for a file already written whole at `finished` (in the target's
// folder, by a writer that names its files itself): checked as written
// whole (synced, its format's ending), given an existing target's
// permissions, and renamed into place (copied where a link leads to another
// file system), so the disk never holds it twice.
std::string moveFileAtomically(const std::filesystem::path& finished, const std::filesystem::path& path);

// Holds back the signals that end a program (SIGINT, SIGTERM, SIGHUP,
// SIGQUIT) while files are written: one arriving then is delivered when the
// holder ends, after the files are all written or all restored, so neither
// a partial file nor a mixed set is left behind.
class SignalsHeld
{
public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

private:
  sigset_t Previous;
};

// The outputs of one run, replaced all or none: each is written atomically;
// unless commit() is called, the ones already replaced get their earlier
// contents back (kept as hard links, or copies, beside them) and new ones are
// removed. The targets must be distinct files (sharedFileError).
class FileSetTransaction
{
public:
  explicit FileSetTransaction(const std::vector<std::filesystem::path>& targets);
  ~FileSetTransaction();
  FileSetTransaction(const FileSetTransaction&) = delete;
  FileSetTransaction& operator=(const FileSetTransaction&) = delete;

  // Keeps what was written: the earlier contents are dropped.
  void commit();

private:
  struct Target
  {
    std::filesystem::path Path, Backup; // Backup empty where no earlier file existed, or none could be kept
    bool Existed;                       // a file without a backup is left, never removed
  };
  std::vector<Target> Targets;
  bool Committed = false;
};
