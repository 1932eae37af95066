#pragma once
// The one way gaitopt writes results (docs/reliability.md): every file of a run is staged in
// a private folder beside its final place and published at the end with one rename per result,
// so a result is the old complete one or the new complete one, never a mix; no planted symbolic
// link is followed; nothing is written outside the named outputs; staging folders of killed runs
// are removed by later runs; SIGINT/SIGTERM/SIGHUP remove the run's own.
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gaitopt {

// An output location that cannot be used (empty, `/`, `.`, under a file, not writable, a name
// over 255 bytes, an input of the run, another output of the run, a directory holding files
// gaitopt did not write); the CLI turns it into exit code 2.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A path the run reads, with the option that named it (for messages): "--gait", "g.yaml".
struct RunInput {
  std::string option;
  std::string path;
};

// The outputs of one run. Declare every result first (each declaration checks its location
// and creates its private staging folder `<parent>/.<name>.gaitopt-XXXXXX`, mode 0700, with
// mkdtemp, locked with flock for the run's life), write the files into the staging paths, then
// commit(). Without commit() (an error, an exception) the staging folders are removed and
// every final name is left as it was.
class OutputTransaction {
 public:
  explicit OutputTransaction(std::vector<RunInput> inputs = {});
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // A directory result at `out` (named `option` in messages), replaced as a whole at commit.
  // Refused: empty, a file, `/`, the current directory or one containing it, a name over 255
  // bytes, a parent that cannot be created or written, an existing directory holding an entry
  // for which ours(name) is false, one holding an input. A link to a directory is replaced in
  // its target's parent. Returns the folder to write the result's files into.
  std::string directory(const std::string& option, const std::string& out,
                        const std::function<bool(const std::string&)>& ours);
  // The same with ours(name) = name is one of `names`.
  std::string directory(const std::string& option, const std::string& out,
                        const std::vector<std::string>& names);

  // A single-file result at `out`. Refused: empty, a directory (`/`, `.`, a trailing `/`), a
  // parent that does not exist, a name over 255 bytes, an input of the run or another output
  // of it. A link at `out` is replaced, not followed. Returns the path to write the file at
  // (inside the staging folder; writeNewFile, or a child process).
  std::string file(const std::string& option, const std::string& out);

  // Publishes every result in declaration order: a directory by rename (an atomic exchange
  // with an existing one, whose old content is then removed), a file by rename over its final
  // name. Throws std::runtime_error when a rename fails (the results before it stay published).
  void commit();

 private:
  struct Result {
    std::string option, target, staging, staged_file;  // staged_file empty: a directory
    int lock_fd = -1;
  };
  Result& stage(const std::string& option, const std::string& out, const std::string& target);
  void requireDistinct(const std::string& option, const std::string& out,
                       const std::string& target, bool is_directory) const;

  std::vector<RunInput> inputs_;
  std::vector<Result> results_;
  bool committed_ = false;
};

// Throws OutputError when `out`, a directory a result file is written into (`sweep-merge
// --out DIR` writes DIR/sweep.csv), is empty, a file, `/`, the current directory or one
// containing it, or has a name over 255 bytes.
void requireOwnDirectory(const std::string& option, const std::string& out);

// Creates `path` (O_CREAT|O_EXCL|O_NOFOLLOW: never an existing file or a link) with `content`
// and syncs it; for the files of a staging folder. Throws std::runtime_error on failure.
void writeNewFile(const std::string& path, const std::string& content);

// One file published as an OutputTransaction of one result: `path` is either the old or the
// new file. Throws OutputError for an unusable `path`, std::runtime_error on a write failure.
void writeFileAtomically(const std::string& path, const std::string& content);

// How long an unlocked staging folder must have been left untouched before a later run removes
// it: its run has ended (the lock dies with the process, SIGKILL included); the delay covers
// the instant between mkdtemp and flock of a run that is starting.
constexpr int kStaleStagingSeconds = 10;

// Blocks SIGINT, SIGTERM and SIGHUP in the calling thread (and the threads it starts later) and
// starts a thread that waits for them: it removes every staging folder of the process, then
// ends the process by the same signal. Call once, first thing in main().
void removeTemporariesOnInterrupt();

}  // namespace gaitopt
