// antcd/file.hpp — the core's file helpers (atomic writes, whole-file reads, folders, printable
// error lines), shared by the library (model files) and its tools. Mesh and text file readers are
// antcd::io's (antcd/load.hpp, antcd/csv.hpp).
#pragma once

#include <antcd/export.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace antcd {

/// Writes `contents` to `path` atomically: into a temporary file in the same folder, flushed, then
/// renamed over `path`. A reader sees the old file or the whole new one, never a part; on failure
/// the temporary file is removed and antcd::Error is thrown naming `path`.
ANTCD_API void write_file_atomic(const std::filesystem::path& path, std::string_view contents);

/// Why `path` cannot be read as a regular file, as a phrase to follow its name: "no such file",
/// "is a directory", "is not a regular file (a device, FIFO or socket)" or "cannot be accessed:
/// <reason>"; empty when it is a regular file. The one check of every file reader (read_file and
/// so Model::load, load_mesh, the CSV readers): a device or a pipe could read forever or block.
ANTCD_API std::string file_problem(const std::filesystem::path& path);

/// Reads a whole file. Throws antcd::Error naming `path` if it is missing, a directory, not a
/// regular file (a device or a pipe, which could read forever or block) or unreadable.
ANTCD_API std::string read_file(const std::filesystem::path& path);

/// Creates the folder `path` and its missing parents (nothing to do if it exists). Throws
/// antcd::Error naming `path` if it cannot be created.
ANTCD_API void create_folders(const std::filesystem::path& path);

/// `text` (an error message) as one printable, bounded line, safe to print on a terminal: line
/// breaks and tabs become blanks; other control bytes (C0, DEL, C1) and bytes that are not UTF-8
/// are shown as \xNN; a quoted input ('...', opened after a blank, '(' or '=' or at the start) is
/// cut after kPrintableQuoteLength characters with "..."; the whole line after kPrintableLineLength
/// bytes. Thread-safe.
inline constexpr std::size_t kPrintableQuoteLength = 80;
inline constexpr std::size_t kPrintableLineLength = 1000;
ANTCD_API std::string printable_line(std::string_view text);

}  // namespace antcd
