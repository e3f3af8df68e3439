#pragma once
#include <string>

namespace vdec {
// Lower-case hex SHA-256 of a byte string (OpenSSL's implementation).
std::string sha256Hex(const std::string& bytes);
}  // namespace vdec
