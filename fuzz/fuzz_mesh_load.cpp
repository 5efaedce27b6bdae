// libFuzzer target: antcd::load_mesh and the Model build on arbitrary bytes.
//
// load_mesh reads files only and picks its reader by the extension first. The first byte
// of an input chooses the extension (byte % 4: 0 .obj, 1 .stl, 2 .ply, 3 .off) and the rest is
// written to a file of this process's own temporary folder and loaded. The seeds in
// fuzz/corpus/mesh start with '0', '1', '2' or '3' accordingly, followed by the mesh file. A
// loaded mesh is built into a Model and queried against a shifted copy of itself. Every
// antcd::Error is an accepted outcome; any other exception, a crash, a sanitizer report, a leak
// (outside assimp, see lsan.supp) or a hang is a finding.
//
// (Loading every input under all four extensions was tried first: assimp's OBJ reader clears a
// 16 MB buffer per file, which held the fuzzer to about 15 inputs a second.)
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>

namespace {

/// A folder of this process's own, removed at exit.
const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern =
        std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/antcd-fuzz-mesh-XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror("antcd fuzz_mesh_load: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(work_dir(), ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

[[noreturn]] void unexpected(const std::filesystem::path& path, const char* what) {
  std::fprintf(stderr, "antcd fuzz_mesh_load: %s: unexpected exception: %s\n",
               path.string().c_str(), what);
  std::abort();
}

void load_and_query(const std::filesystem::path& path) {
  try {
    antcd::Mesh mesh = antcd::load_mesh(path);
    const antcd::Model model(std::move(mesh), {}, path.string());
    const antcd::Transform shifted{antcd::Mat3::Identity(), antcd::Vec3(0.25, 0, 0)};
    (void)antcd::collide(model, {}, model, shifted,
                         {.delta = 0.01, .all_contacts = true, .max_contacts = 64});
  } catch (const antcd::Error&) {
    // A clear refusal: fine.
  } catch (const std::exception& e) {
    unexpected(path, e.what());
  } catch (...) {
    unexpected(path, "not a std::exception");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const extensions[] = {".obj", ".stl", ".ply", ".off"};
  std::filesystem::path path = work_dir() / "input";
  path += extensions[data[0] % 4];
  if (std::FILE* f = std::fopen(path.c_str(), "wb"); f != nullptr) {
    const bool written = size == 1 || std::fwrite(data + 1, 1, size - 1, f) == size - 1;
    if (std::fclose(f) != 0 || !written) std::abort();
  } else {
    std::perror("antcd fuzz_mesh_load: fopen");
    std::abort();
  }
  load_and_query(path);
  std::filesystem::remove(path);
  return 0;
}
