// How much memory work may plan to use: the machine's (or the container's) memory, and the
// budget that refinement and the commands built on it check their estimated peak against
// before allocating anything (docs/io.md "Limits").
#pragma once

#include <cstdint>
#include <string>

namespace limsurf {

/// @brief Bytes of memory this process can have: the physical memory, or the control group's
///   limit (cgroup v2 memory.max, v1 memory.limit_in_bytes) when that is lower; 0 when unknown.
[[nodiscard]] std::int64_t machine_memory_bytes();

/// @brief The default budget for work that estimates its peak memory in advance: 3/4 of
///   machine_memory_bytes() (the rest for the system and the caller's own data); no limit
///   (INT64_MAX) when the machine's memory is unknown.
[[nodiscard]] std::int64_t default_memory_budget();

/// @brief "17.9 GiB", "512 MiB", "800 KiB", "120 bytes": a byte count for messages.
[[nodiscard]] std::string format_bytes(std::int64_t bytes);

/// @brief Parses a memory size: a number with an optional unit K, M, G, T (powers of 1024; a
///   trailing "B" or "iB" is allowed, case-insensitive), e.g. "8G", "512MiB", "1.5g", "1000000".
/// @throws InputError for anything else, or a size that is not positive
[[nodiscard]] std::int64_t parse_memory_size(const std::string& text);

}  // namespace limsurf
