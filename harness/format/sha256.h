// SHA-256 (FIPS 180-4), used to fingerprint a scene's canonical JSON so that a
// golden recorded from an older version of the scene is reported as stale.
#pragma once

#include <string>

namespace impulse::harness {

// The SHA-256 of `bytes` as 64 lowercase hex digits.
std::string sha256_hex(const std::string& bytes);

} // namespace impulse::harness
