// python/src/paths.cpp — see paths.hpp.
#include "paths.hpp"

#include <cerrno>
#include <fstream>
#include <string>
#include <utility>

namespace antcd::python {

namespace py = pybind11;

namespace {

[[noreturn]] void raise_os_error(PyObject* type, int code, const std::string& message,
                                 const std::filesystem::path& path) {
  // OSError(errno, strerror, filename): str() gives "[Errno 2] <message>: '<path>'".
  PyErr_SetObject(type, py::make_tuple(code, message, path.string()).ptr());
  throw py::error_already_set();
}

}  // namespace

std::filesystem::path to_path(py::handle value) {
  auto text = py::module_::import("os").attr("fspath")(value).cast<std::string>();
  // The operating system would read the path only up to a NUL byte, and so open another file.
  if (text.find('\0') != std::string::npos) throw py::value_error("embedded null byte in path");
  return std::filesystem::path(std::move(text));
}

void require_readable_file(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  const std::string role(what);
  if (!std::filesystem::exists(status)) {
    raise_os_error(PyExc_FileNotFoundError, ENOENT, role + " not found", path);
  }
  if (std::filesystem::is_directory(status)) {
    raise_os_error(PyExc_IsADirectoryError, EISDIR, role + " is a directory", path);
  }
  if (!std::filesystem::is_regular_file(status)) {
    raise_os_error(PyExc_OSError, EINVAL, role + " is not a regular file", path);
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe) raise_os_error(PyExc_PermissionError, EACCES, role + " cannot be read", path);
}

}  // namespace antcd::python
