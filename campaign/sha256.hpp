// SHA-256 (FIPS 180-4), written here from the standard, for job identities:
// a job's id is the hex digest of its canonical scene text and solver version.
#pragma once

#include <string>
#include <string_view>

namespace splat::campaign {

// Lower-case hex digest (64 characters) of `data`.
std::string sha256_hex(std::string_view data);

}  // namespace splat::campaign
