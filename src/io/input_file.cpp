#include "gaitopt/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "gaitopt/io/config_error.hpp"

namespace gaitopt {

namespace {

// Why a file of this type cannot be an input; empty for a regular file.
std::string notRegular(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "is a directory, a file is expected";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), a regular file is expected";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, a regular file is expected";
  if (S_ISSOCK(mode)) return "is a socket, a regular file is expected";
  return "is not a regular file";
}

}  // namespace

std::string readInputFile(const std::string& path, std::size_t max_bytes,
                          const std::string& limit) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw ConfigError(path, "", 0, errno == ENOENT ? "no such file" : std::strerror(errno));
  }
  if (!notRegular(st.st_mode).empty()) throw ConfigError(path, "", 0, notRegular(st.st_mode));
  // O_NONBLOCK: should the file have become a FIFO since stat, open does not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw ConfigError(path, "", 0, std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  try {
    if (::fstat(fd, &st) != 0 || !notRegular(st.st_mode).empty())
      throw ConfigError(path, "", 0, notRegular(st.st_mode));
    if (static_cast<std::size_t>(st.st_size) > max_bytes)
      throw ConfigError(path, "", 0, "file larger than " + limit + " (limit)");
    // Read to the end (the file may grow after fstat), never past the limit.
    char buffer[1 << 16];
    while (true) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw ConfigError(path, "", 0, std::string("cannot read: ") + std::strerror(errno));
      if (n == 0) break;
      text.append(buffer, static_cast<std::size_t>(n));
      if (text.size() > max_bytes)
        throw ConfigError(path, "", 0, "file larger than " + limit + " (limit)");
    }
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return text;
}

}  // namespace gaitopt
