// Writes a file under a temporary name in the same folder and renames it into
// place, so an earlier file is never replaced by a partial one; and a set of
// files replaced all or none.
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

// Calls write(temporaryPath); on success renames it to path: to the file a
// symbolic link there names, keeping an existing file's permissions, and
// refusing one this process may not write, as cp does. Returns an empty
// string on success, else the reason; the temporary file never survives.
std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write);

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
    std::filesystem::path Path, Backup; // Backup empty where no earlier file existed
  };
  std::vector<Target> Targets;
  bool Committed = false;
};
