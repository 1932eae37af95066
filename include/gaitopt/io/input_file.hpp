#pragma once
// Reading of the input files (docs/reliability.md): regular files only and within a size
// limit, checked before a byte is read, so that a FIFO never blocks, a device is never read and
// a directory is named as such.
#include <cstddef>
#include <string>

namespace gaitopt {

// The whole of `path`. Throws ConfigError naming the file when it does not exist, is a
// directory, a FIFO, a device or a socket (each with its own message), cannot be read, or holds
// more than `max_bytes` bytes ("file larger than <limit> (limit)", `limit` as given).
std::string readInputFile(const std::string& path, std::size_t max_bytes,
                          const std::string& limit);

}  // namespace gaitopt
