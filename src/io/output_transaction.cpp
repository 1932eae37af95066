#include "gaitopt/io/output_transaction.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

namespace gaitopt {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxNameBytes = 255;  // NAME_MAX of Linux file systems
constexpr const char* kStagingTag = ".gaitopt-";

// Staging folders to remove if the process is interrupted.
struct Temporaries {
  std::mutex mutex;
  std::set<std::string> paths;
};
Temporaries& temporaries() {
  static Temporaries t;
  return t;
}

void track(const std::string& path) {
  std::lock_guard<std::mutex> lock(temporaries().mutex);
  temporaries().paths.insert(path);
}

void untrack(const std::string& path) {
  std::lock_guard<std::mutex> lock(temporaries().mutex);
  temporaries().paths.erase(path);
}

std::string systemError(const std::string& what, const std::string& path) {
  return what + " '" + path + "': " + std::strerror(errno);
}

std::string quote(const std::string& option, const std::string& out) {
  return option + " '" + out + "'";
}

void writeAll(int fd, const std::string& content, const std::string& path) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(systemError("cannot write", path));
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) throw std::runtime_error(systemError("cannot sync", path));
}

void requireShortNames(const std::string& option, const std::string& out) {
  for (const fs::path& part : fs::path(out)) {
    if (part.string().size() > kMaxNameBytes) {
      throw OutputError(quote(option, out) + ": a name longer than " +
                        std::to_string(kMaxNameBytes) + " bytes");
    }
  }
}

// "." + the final name (shortened for NAME_MAX) + ".gaitopt-": the staging folders' prefix.
std::string stagingPrefix(const fs::path& target) {
  return "." + target.filename().string().substr(0, 100) + kStagingTag;
}

// A staging folder of `prefix` whose run has ended: a directory of ours, not locked, untouched
// for kStaleStagingSeconds. The lock taken to test it is kept while it is removed.
void removeIfStale(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid() ||
      std::time(nullptr) - st.st_mtime < kStaleStagingSeconds)
    return;
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ::close(fd);
}

void removeStaleStaging(const fs::path& target) {
  const std::string prefix = stagingPrefix(target);
  std::error_code ec;
  for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string suffix = name.size() > prefix.size() ? name.substr(prefix.size()) : "";
    const bool ours_by_name = name.compare(0, prefix.size(), prefix) == 0 &&
                              suffix.size() >= 6 && suffix.size() <= 10 &&
                              suffix.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNO"
                                                       "PQRSTUVWXYZ0123456789") == std::string::npos;
    if (ours_by_name) removeIfStale(it->path());
  }
}

// `out` made absolute (through its real path when it exists, so that a link to a directory
// is replaced in its target's parent); refuses `/`, the current directory and its ancestors,
// whose replacement would pull the ground from under the user's shell.
fs::path directoryTarget(const std::string& option, const std::string& out) {
  if (out.empty()) throw OutputError(option + ": empty directory name");
  requireShortNames(option, out);
  std::error_code ec;
  const fs::file_status status = fs::status(out, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw OutputError(quote(option, out) + " exists and is not a directory");
  }
  const fs::path target = fs::exists(status) ? fs::canonical(out, ec) : fs::absolute(out, ec);
  if (ec) throw OutputError(quote(option, out) + ": " + ec.message());
  const fs::path normal = target.lexically_normal();
  const fs::path cwd = fs::current_path(ec);
  const fs::path rel = cwd.lexically_relative(normal);
  if (normal == normal.root_path() || (!rel.empty() && *rel.begin() != "..")) {
    throw OutputError(quote(option, out) + " is the current directory or contains it; name a "
                      "directory of its own");
  }
  return normal;
}

// `out` as <real path of its directory>/<name>; a link at `out` itself is kept as a name (it
// is replaced, not followed).
fs::path fileTarget(const std::string& option, const std::string& out) {
  if (out.empty()) throw OutputError(option + ": empty file name");
  requireShortNames(option, out);
  const fs::path path(out);
  const std::string name = path.filename().string();
  std::error_code ec;
  if (name.empty() || name == "." || name == ".." || fs::is_directory(path, ec)) {
    throw OutputError(quote(option, out) + " is a directory, a file is expected");
  }
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(parent, ec)) {
    throw OutputError(quote(option, out) + ": its directory '" + parent.string() +
                      "' does not exist");
  }
  const fs::path real = fs::canonical(parent, ec);
  if (ec) throw OutputError(quote(option, out) + ": " + ec.message());
  return real / name;
}

void requireOnlyOurs(const fs::path& target, const std::string& option, const std::string& out,
                     const std::function<bool(const std::string&)>& ours) {
  std::error_code ec;
  if (!fs::is_directory(target, ec)) return;
  for (fs::directory_iterator it(target, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!ours(name)) {
      throw OutputError(quote(option, out) + " holds '" + name +
                        "', which gaitopt did not write; gaitopt replaces the whole directory, "
                        "so give a new or empty one");
    }
  }
  if (ec) throw OutputError(quote(option, out) + " cannot be listed: " + ec.message());
}

// `inner` is `outer` or lies inside it (both absolute and normal).
bool within(const fs::path& inner, const fs::path& outer) {
  const fs::path rel = inner.lexically_relative(outer);
  return !rel.empty() && *rel.begin() != "..";
}

// The names an input is known by: as given (absolute, normal) and its real path.
std::vector<fs::path> inputNames(const std::string& input) {
  std::error_code ec;
  std::vector<fs::path> names{fs::absolute(input, ec).lexically_normal()};
  const fs::path real = fs::weakly_canonical(input, ec);
  if (!ec) names.push_back(real.lexically_normal());
  return names;
}

}  // namespace

OutputTransaction::OutputTransaction(std::vector<RunInput> inputs) : inputs_(std::move(inputs)) {}

OutputTransaction::~OutputTransaction() {
  for (Result& r : results_) {
    if (!committed_) {
      std::error_code ignored;
      fs::remove_all(r.staging, ignored);
      untrack(r.staging);
    }
    if (r.lock_fd >= 0) ::close(r.lock_fd);
  }
}

void OutputTransaction::requireDistinct(const std::string& option, const std::string& out,
                                        const std::string& target, bool is_directory) const {
  for (const RunInput& input : inputs_) {
    if (input.path.empty()) continue;
    for (const fs::path& name : inputNames(input.path)) {
      if (name == fs::path(target)) {
        throw OutputError(quote(option, out) + " names the input " +
                          quote(input.option, input.path) + "; give another output name");
      }
      if (is_directory && within(name, target)) {
        throw OutputError(quote(option, out) + " holds the input " +
                          quote(input.option, input.path) +
                          ", which replacing the directory would remove");
      }
    }
  }
  for (const Result& r : results_) {
    if (within(target, r.target) || within(r.target, target)) {
      throw OutputError(quote(option, out) + " is the same as, or inside, the output " +
                        r.option + " of this run");
    }
  }
}

OutputTransaction::Result& OutputTransaction::stage(const std::string& option,
                                                    const std::string& out,
                                                    const std::string& target) {
  removeStaleStaging(target);
  std::string name = (fs::path(target).parent_path() / (stagingPrefix(target) + "XXXXXX")).string();
  if (::mkdtemp(name.data()) == nullptr) {
    throw OutputError(systemError(quote(option, out) + " cannot be written: cannot create", name));
  }
  track(name);
  Result r;
  r.option = option;
  r.target = target;
  r.staging = name;
  // Locked for the run's life: a later run removes the folder only once the lock is gone.
  r.lock_fd = ::open(name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (r.lock_fd < 0 || ::flock(r.lock_fd, LOCK_EX | LOCK_NB) != 0) {
    const std::string message = systemError("cannot lock", name);
    if (r.lock_fd >= 0) ::close(r.lock_fd);
    std::error_code ignored;
    fs::remove_all(name, ignored);
    untrack(name);
    throw std::runtime_error(message);
  }
  results_.push_back(r);
  return results_.back();
}

std::string OutputTransaction::directory(const std::string& option, const std::string& out,
                                         const std::function<bool(const std::string&)>& ours) {
  const fs::path target = directoryTarget(option, out);
  requireOnlyOurs(target, option, out, ours);
  requireDistinct(option, out, target.string(), true);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw OutputError(quote(option, out) + ": cannot create its parent: " + ec.message());
  Result& r = stage(option, out, target.string());
  // mkdtemp's folder is private (0700); the published directory gets the usual mode.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(r.lock_fd, 0777 & ~mask);
  return r.staging;
}

std::string OutputTransaction::directory(const std::string& option, const std::string& out,
                                         const std::vector<std::string>& names) {
  return directory(option, out, [names](const std::string& name) {
    for (const std::string& n : names)
      if (n == name) return true;
    return false;
  });
}

std::string OutputTransaction::file(const std::string& option, const std::string& out) {
  const fs::path target = fileTarget(option, out);
  requireDistinct(option, out, target.string(), false);
  Result& r = stage(option, out, target.string());
  r.staged_file = (fs::path(r.staging) / target.filename()).string();
  return r.staged_file;
}

void OutputTransaction::commit() {
  for (Result& r : results_) {
    const bool is_file = !r.staged_file.empty();
    {
      // Under the lock, so an interrupt sees either the staging folder or the result in place.
      std::lock_guard<std::mutex> lock(temporaries().mutex);
      if (is_file) {
        if (std::rename(r.staged_file.c_str(), r.target.c_str()) != 0)
          throw std::runtime_error(systemError("cannot put '" + r.staged_file + "' in place of",
                                               r.target));
      } else if (std::rename(r.staging.c_str(), r.target.c_str()) != 0) {
        // The target is a non-empty directory: swap both names in one step, so it is never
        // missing; the old content is then at the staging name.
        if (::renameat2(AT_FDCWD, r.staging.c_str(), AT_FDCWD, r.target.c_str(),
                        RENAME_EXCHANGE) != 0)
          throw std::runtime_error(systemError("cannot put '" + r.staging + "' in place of",
                                               r.target));
      } else {
        temporaries().paths.erase(r.staging);
      }
    }
    std::error_code ignored;
    fs::remove_all(r.staging, ignored);  // the old content of a directory, if any
    untrack(r.staging);
  }
  committed_ = true;
}

void requireOwnDirectory(const std::string& option, const std::string& out) {
  directoryTarget(option, out);
}

void writeNewFile(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(systemError("cannot create", path));
  try {
    writeAll(fd, content, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw std::runtime_error(systemError("cannot close", path));
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  OutputTransaction transaction;
  writeNewFile(transaction.file("output", path), content);
  transaction.commit();
}

void removeTemporariesOnInterrupt() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals]() {
    int received = 0;
    if (sigwait(&signals, &received) != 0) return;
    // The lock is kept until the process ends: no temporary is registered or committed after
    // the removal. Workers still writing may add a file while remove_all walks a directory (its
    // last rmdir then fails), so each removal is repeated until the path is gone.
    temporaries().mutex.lock();
    for (const std::string& path : temporaries().paths) {
      std::error_code ec;
      for (int attempt = 0; attempt < 100 && fs::symlink_status(path, ec).type() !=
                                                  fs::file_type::not_found;
           ++attempt) {
        fs::remove_all(path, ec);
      }
    }
    std::signal(received, SIG_DFL);
    pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
    std::raise(received);
  }).detach();
}

}  // namespace gaitopt
