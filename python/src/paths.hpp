// python/src/paths.hpp — file arguments: os.PathLike to a path, and OSError for missing files.
#pragma once

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string_view>

namespace antcd::python {

/// str or os.PathLike to a path (TypeError otherwise, as os.fspath raises; ValueError for a path
/// holding a NUL byte, as Python's open raises).
std::filesystem::path to_path(pybind11::handle value);

/// Raises FileNotFoundError / IsADirectoryError / PermissionError (OSError subclasses, with errno
/// and filename set) when `path` cannot be opened as a regular file for reading. `what` names the
/// file's role in the message ("mesh file", "scene file").
void require_readable_file(const std::filesystem::path& path, std::string_view what);

}  // namespace antcd::python
