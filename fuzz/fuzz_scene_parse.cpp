// libFuzzer target: antcd::parse_scene on arbitrary bytes, and antcd::parse_vertex_frames (a
// deforming object's side file) on the inputs that start with its magic (fuzz/corpus/scene holds
// both kinds, so one target and its CI minute cover both readers).
//
// Every antcd::Error (SceneError) is an accepted outcome; any other exception, a crash or a
// sanitizer report is a finding. A scene that parses must also survive the round trip through
// scene_to_json: the written text parses again to the same objects and frames. Side files that
// decode must hold vertex_count x frames finite positions and encode back to the same bytes.
#include <antcd/scene.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <span>
#include <string>
#include <string_view>

#include "finding.hpp"

namespace {

[[noreturn]] void finding(const char* what, const char* detail) {
  antcd::fuzz::finding("fuzz_scene_parse", what, detail);
}

void fuzz_vertex_frames(const std::uint8_t* data, std::size_t size) {
  antcd::VertexFrames frames;
  try {
    frames = antcd::parse_vertex_frames(std::span<const std::uint8_t>(data, size), "fuzz.avf");
  } catch (const antcd::Error&) {
    return;  // a clear refusal: fine
  } catch (const std::exception& e) {
    finding("unexpected exception from parse_vertex_frames", e.what());
  } catch (...) {
    finding("unexpected exception from parse_vertex_frames", "not a std::exception");
  }
  if (frames.vertex_count == 0 || frames.frames == 0 ||
      frames.positions.size() != frames.frames * frames.vertex_count) {
    finding("parse_vertex_frames", "accepted counts that do not match the positions");
  }
  for (const antcd::Vec3& p : frames.positions) {
    if (!p.allFinite()) finding("parse_vertex_frames", "accepted a position that is not finite");
  }
  try {
    const std::string bytes = antcd::vertex_frames_bytes(frames);
    if (bytes.size() != size || std::memcmp(bytes.data(), data, size) != 0) {
      finding("vertex frames round trip", "the bytes written differ from the bytes read");
    }
  } catch (const std::exception& e) {
    finding("vertex frames round trip failed", e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size >= sizeof antcd::kVertexFramesMagic &&
      std::memcmp(data, antcd::kVertexFramesMagic, sizeof antcd::kVertexFramesMagic) == 0) {
    fuzz_vertex_frames(data, size);
    return 0;
  }
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  antcd::SceneDescription scene;
  try {
    scene = antcd::parse_scene(text, "/fuzz", "fuzz.json");
  } catch (const antcd::Error&) {
    return 0;  // a clear refusal: fine
  } catch (const std::exception& e) {
    finding("unexpected exception from parse_scene", e.what());
  } catch (...) {
    finding("unexpected exception from parse_scene", "not a std::exception");
  }
  try {
    const std::string written = antcd::scene_to_json(scene);
    const antcd::SceneDescription again = antcd::parse_scene(written, "/fuzz", "again.json");
    if (again.frames != scene.frames || again.objects.size() != scene.objects.size()) {
      finding("round trip", "frames or object count changed");
    }
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      if (again.objects[i].name != scene.objects[i].name ||
          again.objects[i].mesh != scene.objects[i].mesh ||
          again.objects[i].poses.size() != scene.objects[i].poses.size()) {
        finding("round trip", "an object changed");
      }
    }
  } catch (const std::exception& e) {
    finding("round trip through scene_to_json failed", e.what());
  }
  return 0;
}
