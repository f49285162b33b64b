// What a run knows about the build that made it. Two builds with the same build_id() (compiler,
// flags, hairfit version, machine) give bit-identical stage values for the same sources, so
// `hairfit check` compares digests exactly between them and with tolerances otherwise.
// source_fingerprint() changes with every edit of lib/ or spec/; the stage cache keys on it.
#pragma once
#include <string>

namespace hairfit {

std::string build_id();            // e.g. "hairfit 0.1.0; gcc 12.2.0; Release -O3 -DNDEBUG ...; x86_64"
std::string source_fingerprint();  // SHA-256 of lib/ and spec/ at build time (64 hex digits)

}  // namespace hairfit
