#include "OpalAtomicFile.h"

#include <system_error>
#include <unistd.h>

std::string writeFileAtomically(
  const std::filesystem::path& path, const std::function<bool(const std::string&)>& write)
{
  // Keep the extension last: writers pick the format from it.
  std::filesystem::path temporary = path;
  temporary.replace_filename(
    "." + path.stem().string() + ".partial-" + std::to_string(::getpid()) + path.extension().string());
  if (!write(temporary.string()))
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "could not write " + path.string();
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error)
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return "could not move the finished file to " + path.string() + ": " + error.message();
  }
  return {};
}

namespace
{
// A name beside path for its earlier contents.
std::filesystem::path backupName(const std::filesystem::path& path)
{
  std::filesystem::path backup = path;
  backup.replace_filename("." + path.filename().string() + ".earlier-" + std::to_string(::getpid()));
  return backup;
}
} // namespace

FileSetTransaction::FileSetTransaction(const std::vector<std::filesystem::path>& targets)
{
  for (const std::filesystem::path& path : targets)
  {
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
