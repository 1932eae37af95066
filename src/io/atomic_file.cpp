#include "gaitopt/io/atomic_file.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <set>
#include <thread>

namespace gaitopt {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxNameBytes = 255;  // NAME_MAX of Linux file systems

// Temporaries to remove if the process is interrupted.
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

std::string randomSuffix() {
  static std::mutex mutex;
  static std::mt19937_64 rng(std::random_device{}());
  std::lock_guard<std::mutex> lock(mutex);
  const char* chars = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string s;
  for (int i = 0; i < 10; ++i) s += chars[rng() % 36];
  return s;
}

// "<dir>/.<name, shortened>.<tag>-<random>": hidden, and short enough for NAME_MAX.
std::string temporarySibling(const fs::path& path, const char* tag) {
  return (path.parent_path() / ("." + path.filename().string().substr(0, 100) + "." + tag + "-" +
                                randomSuffix()))
      .string();
}

std::string systemError(const std::string& what, const std::string& path) {
  return what + " '" + path + "': " + std::strerror(errno);
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

void requireShortNames(const fs::path& path, const std::string& out) {
  for (const fs::path& part : path) {
    if (part.string().size() > kMaxNameBytes) {
      throw OutputError("--out '" + out + "': a name longer than " +
                        std::to_string(kMaxNameBytes) + " bytes");
    }
  }
}

// `out` made absolute (through its real path when it exists, so that a link to a directory
// is replaced in its target's parent); refuses the current directory and its ancestors, whose
// replacement would pull the ground from under the user's shell.
fs::path resolvedTarget(const std::string& out) {
  if (out.empty()) throw OutputError("--out: empty directory name");
  requireShortNames(fs::path(out), out);
  std::error_code ec;
  const fs::file_status status = fs::status(out, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw OutputError("--out '" + out + "' exists and is not a directory");
  }
  const fs::path target = fs::exists(status) ? fs::canonical(out, ec) : fs::absolute(out, ec);
  if (ec) throw OutputError("--out '" + out + "': " + ec.message());
  const fs::path normal = target.lexically_normal();
  const fs::path cwd = fs::current_path(ec);
  const fs::path rel = cwd.lexically_relative(normal);
  if (normal == normal.root_path() || (!rel.empty() && *rel.begin() != "..")) {
    throw OutputError("--out '" + out + "' is the current directory or contains it; name a "
                      "directory of its own");
  }
  return normal;
}

void requireOnlyOurs(const fs::path& target, const std::string& out,
                     const std::function<bool(const std::string&)>& ours) {
  std::error_code ec;
  if (!fs::is_directory(target, ec)) return;
  for (fs::directory_iterator it(target, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!ours(name)) {
      throw OutputError("--out '" + out + "' holds '" + name +
                        "', which gaitopt did not write; gaitopt replaces the whole directory, "
                        "so give a new or empty one");
    }
  }
  if (ec) throw OutputError("--out '" + out + "' cannot be listed: " + ec.message());
}

}  // namespace

void writeFileAtomically(const std::string& path, const std::string& content) {
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 16; ++attempt) {
    tmp = temporarySibling(path, "tmp");
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) throw std::runtime_error(systemError("cannot create", tmp));
  }
  if (fd < 0) throw std::runtime_error(systemError("cannot create", tmp));
  track(tmp);
  try {
    writeAll(fd, content, tmp);
    if (::close(fd) != 0) {
      fd = -1;
      throw std::runtime_error(systemError("cannot close", tmp));
    }
    fd = -1;
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
      throw std::runtime_error(systemError("cannot rename '" + tmp + "' to", path));
    }
  } catch (...) {
    if (fd >= 0) ::close(fd);
    std::remove(tmp.c_str());
    untrack(tmp);
    throw;
  }
  untrack(tmp);
}

StagedDirectory::StagedDirectory(const std::string& out,
                                 const std::function<bool(const std::string&)>& ours) {
  const fs::path target = resolvedTarget(out);
  requireOnlyOurs(target, out, ours);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw OutputError("--out '" + out + "': cannot create its parent: " + ec.message());
  for (int attempt = 0; staging_.empty() && attempt < 16; ++attempt) {
    const std::string candidate = temporarySibling(target, "gaitopt");
    if (::mkdir(candidate.c_str(), 0777) == 0) {
      staging_ = candidate;
    } else if (errno != EEXIST) {
      throw OutputError(systemError("--out '" + out + "' cannot be written: cannot create",
                                    candidate));
    }
  }
  if (staging_.empty()) throw OutputError("--out '" + out + "': no free temporary name");
  track(staging_);
  target_ = target.string();
}

StagedDirectory::~StagedDirectory() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  untrack(staging_);
}

void StagedDirectory::commit() {
  {
    // Under the lock, so an interrupt sees either the temporary or the result in place.
    std::lock_guard<std::mutex> lock(temporaries().mutex);
    if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
      // `out` exists (a non-empty directory): swap both names in one step, so `out` is never
      // missing; the old content is then at the temporary name.
      if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) !=
          0) {
        throw std::runtime_error(systemError("cannot put '" + staging_ + "' in place of",
                                             target_));
      }
    } else {
      temporaries().paths.erase(staging_);
    }
  }
  committed_ = true;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);  // the old content, if any
  untrack(staging_);
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
