#include <antcd/error.hpp>
#include <antcd/io.hpp>

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

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": is a directory");
  if (!std::filesystem::exists(path, ec)) throw Error(path.string() + ": no such file");
  // Devices and pipes (/dev/zero, a FIFO with no writer) would read forever or block.
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(path.string() + ": is not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path.string() + ": read failed");
  return text.str();
}

void create_folders(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) throw Error(path.string() + ": cannot create the folder: " + ec.message());
}

}  // namespace antcd
