#include <antcd/error.hpp>
#include <antcd/file.hpp>

#include "util/huge_pages.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

#if defined(_WIN32)
#include <io.h>
#else
#include <unistd.h>
#endif

namespace antcd {

namespace {

// Flushes the file's data to the device (POSIX fsync, Windows _commit). 0 on success.
int sync_to_disk(std::FILE* file) {
#if defined(_WIN32)
  return ::_commit(::_fileno(file));
#else
  return ::fsync(::fileno(file));
#endif
}

// A temporary name beside the target, unique across threads and processes: the target's own name,
// hidden, with a random suffix. The file is created exclusively, so a clash fails loudly.
std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<std::uint64_t> counter{0};
  thread_local std::mt19937_64 rng{std::random_device{}()};
  const std::uint64_t tag = rng() ^ (counter.fetch_add(1) * 0x9E3779B97F4A7C15ULL);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(tag));
  // Built with append(): GCC 12 reports a false -Wrestrict on chained operator+ here.
  std::string name(".");
  name.append(target.filename().string()).append(".tmp-").append(hex);
  std::filesystem::path tmp = target;
  tmp.replace_filename(name);
  return tmp;
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::string_view contents) {
  const auto fail = [&](const std::string& why) -> void {
    throw Error(path.string() + ": cannot write: " + why);
  };
  if (path.filename().empty()) fail("the path names no file");
  // The rename below would replace a device, FIFO or socket with a regular file (as root,
  // `--out /dev/null` would turn /dev/null into a file). A directory is left to the rename, which
  // fails on it without harm.
  std::error_code status_error;
  const auto status = std::filesystem::status(path, status_error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_directory(status)) {
    fail("it exists and is not a regular file (a device, FIFO or socket is never replaced)");
  }
  const std::filesystem::path tmp = temporary_beside(path);
  std::FILE* file = std::fopen(tmp.string().c_str(), "wbx");
  if (file == nullptr) fail(std::strerror(errno));

  // Every exit that does not reach the rename closes and removes the temporary file.
  bool committed = false;
  struct Cleanup {
    std::FILE*& file;
    const std::filesystem::path& tmp;
    bool& committed;
    ~Cleanup() {
      if (file != nullptr) std::fclose(file);
      if (!committed) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
      }
    }
  } cleanup{file, tmp, committed};

  if (!contents.empty() &&
      std::fwrite(contents.data(), 1, contents.size(), file) != contents.size()) {
    fail(std::strerror(errno));
  }
  if (std::fflush(file) != 0) fail(std::strerror(errno));
  // Durable before the rename publishes it, so a crash never leaves a torn file under `path`.
  if (sync_to_disk(file) != 0) fail(std::strerror(errno));
  const int closed = std::fclose(file);
  file = nullptr;
  if (closed != 0) fail(std::strerror(errno));
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail(ec.message());
  committed = true;
}

std::string file_problem(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  switch (status.type()) {
    case std::filesystem::file_type::regular:
      return {};
    case std::filesystem::file_type::not_found:
      return "no such file";
    case std::filesystem::file_type::directory:
      return "is a directory";
    case std::filesystem::file_type::none:
    case std::filesystem::file_type::unknown:
      if (ec) return "cannot be accessed: " + printable_line(ec.message());
      return "cannot be accessed";
    default:
      // Devices and pipes (/dev/zero, a FIFO with no writer) would read forever or block.
      return "is not a regular file (a device, FIFO or socket)";
  }
}

std::string read_file(const std::filesystem::path& path) {
  if (const std::string problem = file_problem(path); !problem.empty()) {
    throw Error(path.string() + ": " + problem);
  }
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open for reading");
  // Read in one piece into a string of the file's size (a large model file is read once, not
  // through a growing stream buffer and a copy), then whatever a growing file added meanwhile.
  std::string text;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0 && size < text.max_size()) {
    text.reserve(static_cast<std::size_t>(size));
    detail::advise_huge_pages(text.data(), text.capacity());  // a large file: fewer page faults
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
  }
  if (in.good()) {
    std::ostringstream rest;
    rest << in.rdbuf();
    text += rest.str();
  }
  if (in.bad()) throw Error(path.string() + ": read failed");
  return text;
}

void create_folders(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) throw Error(path.string() + ": cannot create the folder: " + ec.message());
}

namespace {

// Length of the valid UTF-8 sequence (2..4 bytes, no overlong form, no surrogate, no C1 control)
// starting at text[i], or 0.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t n = 0;
  unsigned char lo = 0x80;
  unsigned char hi = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    n = 2;
    if (lead == 0xC2) lo = 0xA0;  // U+0080..U+009F are the C1 controls
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    n = 3;
    if (lead == 0xE0) lo = 0xA0;
    if (lead == 0xED) hi = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    n = 4;
    if (lead == 0xF0) lo = 0x90;
    if (lead == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}

}  // namespace

std::string printable_line(std::string_view text) {
  std::string out;
  out.reserve(std::min(text.size(), kPrintableLineLength) + 8);
  bool quoted = false;    // inside a quoted input
  std::size_t shown = 0;  // its characters printed so far
  bool cut = false;       // its rest is being skipped
  for (std::size_t i = 0; i < text.size() && out.size() < kPrintableLineLength;) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t n = 1;
    if (c == '\'' && quoted) {
      quoted = false;
      if (cut) out += "...";
      cut = false;
      out += '\'';
      ++i;
      continue;
    }
    if (c == '\'' && (out.empty() || out.back() == ' ' || out.back() == '(' || out.back() == '=')) {
      quoted = true;
      shown = 0;
      out += '\'';
      ++i;
      continue;
    }
    if (c >= 0x80) n = utf8_length(text, i);
    if (quoted && !cut && shown == kPrintableQuoteLength) cut = true;
    if (!cut) {
      if (c == '\n' || c == '\r' || c == '\t') {
        out += ' ';
      } else if (c < 0x20 || c == 0x7F || n == 0) {
        char hex[5];
        std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(c));
        out += hex;
        n = 1;
      } else {
        out.append(text.substr(i, n));
      }
      ++shown;
    }
    i += n == 0 ? 1 : n;
  }
  if (cut) out += "...";
  if (out.size() >= kPrintableLineLength) out += "...";
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace antcd
