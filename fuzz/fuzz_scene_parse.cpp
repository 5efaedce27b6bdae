// libFuzzer target: antcd::parse_scene on arbitrary bytes.
//
// Every antcd::Error (SceneError) is an accepted outcome; any other exception, a crash or a
// sanitizer report is a finding. A scene that parses must also survive the round trip through
// scene_to_json: the written text parses again to the same objects and frames.
#include <antcd/scene.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "finding.hpp"

namespace {

[[noreturn]] void finding(const char* what, const char* detail) {
  antcd::fuzz::finding("fuzz_scene_parse", what, detail);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
