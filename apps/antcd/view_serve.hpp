// `antcd view --serve`: a small HTTP/1.0 server on 127.0.0.1 for scenes too large to inline.
#pragma once

#include <cstdint>
#include <string>

namespace antcd::cli {

struct ServedFile {
  std::string path;  ///< e.g. "/" or "/antcd-view.bin"
  std::string content_type;
  const std::string* body = nullptr;
};

/// Serves `files` (GET and HEAD) on 127.0.0.1:`port` (0: any free port) until SIGINT or SIGTERM,
/// then returns 0. Bounded: at most 16 connections at once (one thread each), requests over
/// 16 KiB refused, 10 s to read a request and to send each chunk; anything else than the listed
/// paths is 404. Prints the URL on stdout once listening. Throws UsageError when the port cannot be
/// bound.
int serve_files(const ServedFile* files, std::size_t count, std::uint16_t port);

}  // namespace antcd::cli
