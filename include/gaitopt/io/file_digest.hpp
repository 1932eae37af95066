#pragma once
// SHA-256 digests (OpenSSL EVP) that tie an exported trajectory or model to the exact robot
// and gait files it was computed from.
#include <string>

namespace gaitopt {

// Lower-case hexadecimal SHA-256 of `bytes`.
std::string sha256Hex(const std::string& bytes);

// The file's bytes; throws std::runtime_error naming the file if unreadable.
std::string fileBytes(const std::string& path);

// SHA-256 of the file's contents; throws std::runtime_error naming the file if unreadable.
std::string fileSha256(const std::string& path);

}  // namespace gaitopt
