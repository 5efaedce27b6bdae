// antcd/io.hpp — small file helpers shared by the library and its tools.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace antcd {

/// Writes `contents` to `path` atomically: into a temporary file in the same folder, flushed, then
/// renamed over `path`. A reader sees the old file or the whole new one, never a part; on failure
/// the temporary file is removed and antcd::Error is thrown naming `path`.
void write_file_atomic(const std::filesystem::path& path, std::string_view contents);

/// Reads a whole file. Throws antcd::Error naming `path` if it is missing, a directory, not a
/// regular file (a device or a pipe, which could read forever or block) or unreadable.
std::string read_file(const std::filesystem::path& path);

}  // namespace antcd
