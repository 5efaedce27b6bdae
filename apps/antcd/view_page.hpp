// The page `antcd view` writes or serves: a scene, its meshes and poses, and up to two run
// results, checked against each other and packed for the browser viewer (viewer/).
//
// Packing: a JSON description ("antcd-view/1") plus one binary blob of little-endian float32
// vertex positions (scale applied), uint32 triangle indices and float32 poses (12 numbers each:
// the rotation matrix row by row, then the translation). The JSON refers to the blob by
// [byte offset, element count]; every array starts on a 4-byte boundary. The blob goes into the
// HTML as base64 (self-contained file) or is served as-is (--serve).
//
// Deforming objects (the scene's "vertex_frames"): the object's "vertex_frames" holds every
// frame's vertex positions, float32, scale applied, model frame (frame 0's vertices, then frame
// 1's...: frames x vertices x 3; live pages: "vertex_frames64", float64, instead), so such an
// object costs 12 n F bytes (live: 24 n F), half (live: all) of its side file's size. Their total
// is capped at kMaxVertexFrameBytes. Objects with "self_collision" say so ("self_collision":
// true). A result's self pairs (i, i) are in its "pairs" like the others; its "self_triangles"
// (present when some frame has one) holds per frame the list [object, [offset, count]] of each
// self pair's intersecting triangle pairs (uint32 a, b per pair: the result's "self_pairs").
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "shared/run_result.hpp"

namespace antcd::cli {

/// The most bytes the deforming objects' vertex frames may take in a page's blob (base64 makes
/// the page a third larger): antcd view refuses a scene beyond it, naming the object.
inline constexpr std::size_t kMaxVertexFrameBytes = std::size_t{256} << 20;

struct ViewResult {
  std::filesystem::path source;  ///< the result file (its name labels the result in the page)
  shared::RunResult run;
};

/// Reads and parses a run result file. Throws antcd::Error naming the file.
ViewResult load_view_result(const std::filesystem::path& path);

struct ViewInputs {
  std::filesystem::path scene;
  std::vector<ViewResult> results;  ///< at most two: the first is the reference
  /// Exact contact points drawn per reported pair and frame, at most this many (0: none).
  std::size_t contacts_per_pair = 16;
  /// The live page (`antcd view --live`): the payload also carries the meshes and poses in
  /// float64 ("positions64", "poses64"), which the page's WebAssembly World queries.
  bool live = false;
};

struct ViewPayload {
  std::string json;  ///< the "antcd-view/1" description
  std::string blob;  ///< the binary arrays it refers to
  std::string title;
  std::size_t objects = 0;
  std::size_t frames = 0;
  bool live = false;
};

/// Loads and checks everything. Throws antcd::Error or UsageError naming the file (and the
/// object, frame or pair) for: an unreadable or malformed scene or result, a missing or
/// unreadable mesh, a result recorded for another scene file, a result frame out of the scene's
/// range or listed twice, a pair naming an object the scene does not have, a self pair's triangle
/// out of its mesh's range, more than two results, deforming objects' vertex frames beyond
/// kMaxVertexFrameBytes.
ViewPayload build_view_payload(const ViewInputs& inputs);

/// The viewer's bundled JavaScript: $ANTCD_VIEWER_JS when set (an error if it does not exist),
/// else the first of the install location
/// <prefix>/share/antcd/antcd-viewer.js and the build tree's viewer/antcd-viewer.js, both relative
/// to the running executable. Throws UsageError saying how to build it when none exists.
/// live: the live page's bundle instead (antcd-live.js, $ANTCD_LIVE_JS; the viewer with the
/// WebAssembly build of antcd inside, built when Emscripten is installed).
std::filesystem::path locate_viewer_bundle(bool live = false);

enum class PageMode { SelfContained, Served };

/// The HTML page: the bundle inline, the description inline, the blob inline as base64
/// (SelfContained) or fetched from ./antcd-view.bin (Served). A Content-Security-Policy forbids
/// every network access (Served: same origin only); a live payload's page may also compile
/// WebAssembly ('wasm-unsafe-eval'), nothing else.
std::string render_page(const ViewPayload& payload, const std::string& bundle_js, PageMode mode);

/// build_view_payload, locate_viewer_bundle and render_page (SelfContained), then writes the page
/// to `out` atomically. Returns the payload's summary (objects, frames).
ViewPayload write_view_file(const ViewInputs& inputs, const std::filesystem::path& out);

/// Standard base64 (RFC 4648, with padding).
std::string base64_encode(const std::string& bytes);

}  // namespace antcd::cli
