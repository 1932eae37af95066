#pragma once
// Safe writing of outputs (docs/reliability.md): nothing half-written, no planted symbolic
// link followed, a run's files appearing together, and temporaries removed on SIGINT/SIGTERM.
#include <functional>
#include <stdexcept>
#include <string>

namespace gaitopt {

// An output location that cannot be used (`--out` empty, under a file, not writable, a name
// over 255 bytes, holding files gaitopt did not write); the CLI turns it into exit code 2.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `content` to a new temporary file beside `path` (random name, created with
// O_CREAT | O_EXCL | O_NOFOLLOW, so a planted link is never followed), syncs it and renames it
// over `path`; rename replaces a link at `path` itself, not its target. `path` is then either
// the old or the new file, never a mix. Throws std::runtime_error on a write failure.
void writeFileAtomically(const std::string& path, const std::string& content);

// A run's output directory written as a whole. The constructor creates a temporary sibling
// directory (<parent>/.<name>.gaitopt-XXXXXX) — which also proves that `out` can be written,
// before any work — and the run writes into path(); commit() puts it in place of `out` (an
// atomic exchange when `out` exists) and removes the old content. An interrupted or failed run
// leaves `out` as it was: the temporary is removed by the destructor and, for SIGINT/SIGTERM,
// by the handler of removeTemporariesOnInterrupt().
class StagedDirectory {
 public:
  // Throws OutputError when `out` is empty, exists and is not a directory, is the current
  // directory or one of its ancestors, has a component over 255 bytes, cannot be created or
  // written, or exists and holds an entry for which `ours(name)` is false (gaitopt would
  // otherwise replace files it did not write).
  StagedDirectory(const std::string& out, const std::function<bool(const std::string&)>& ours);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::string& path() const { return staging_; }  // write the outputs here
  void commit();

 private:
  std::string target_;
  std::string staging_;
  bool committed_ = false;
};

// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread (and the threads it starts later) and
// starts a thread that waits for them: it removes every temporary file and directory still
// registered by writeFileAtomically and StagedDirectory, then ends the process by the same
// signal. Call once, first thing in main().
void removeTemporariesOnInterrupt();

}  // namespace gaitopt
