// load_mesh: reads any mesh file assimp understands into an antcd::Mesh; OBJ is read in double
// precision instead (polygon_soup.hpp, load_obj.cpp), the other formats through assimp.
//
// OFF and PLY keep their file's precision although assimp reads them into floats: assimp reads
// the structure (faces, corners, vertex count), the coordinates are re-read from the file's bytes
// along the same layout (exact_coordinates.hpp), and each re-read coordinate must agree with
// assimp's float for the same vertex before any is used. Vertices are paired by position in the
// scene assimp builds before any post-processing, where its OFF and PLY readers keep the file's
// vertex order (joining or sorting would break the pairing), and that scene's polygons go the OBJ
// way (soup_to_mesh). Whenever the pairing is not certain, the file loads as before, in floats.
//
// Every call uses its own Assimp::Importer, so concurrent loads share no state. antcd never
// creates assimp's DefaultLogger (a process-wide object): while no logger exists assimp logs into
// its NullLogger, so loading prints nothing. The one exception seen over all of assimp-testmodels:
// the OpenDDL parser inside the OpenGEX reader writes "nullptr returned by creating DDLNode." to
// stderr for OpenGEX/empty_camera.ogex, past assimp's logger.
#include <antcd/bvh.hpp>
#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include "io/exact_coordinates.hpp"
#include "io/ply_layout.hpp"
#include "io/polygon_soup.hpp"
#include "io/stl_binary.hpp"

#include <assimp/config.h>
#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_set>
#include <utility>
#include <vector>

namespace antcd {
namespace {

using Affine = Eigen::Matrix<Scalar, 4, 4>;

/// assimp's matrices are row-major with the translation in the fourth column, the same
/// column-vector convention as Eigen's; they are widened to double before being composed.
Affine to_affine(const aiMatrix4x4& m) {
  Affine a;
  a << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return a;
}

/// One placement of an aiMesh in the scene: the mesh and the accumulated node transform.
struct Instance {
  const aiMesh* mesh = nullptr;
  Affine transform = Affine::Identity();
};

std::vector<Instance> collect_instances(const aiScene& scene, const std::string& source) {
  std::vector<Instance> out;
  if (scene.mMeshes == nullptr) return out;
  if (scene.mRootNode == nullptr) {
    // No scene graph at all: every mesh once, untransformed.
    for (unsigned i = 0; i < scene.mNumMeshes; ++i)
      out.push_back({scene.mMeshes[i], Affine::Identity()});
    return out;
  }
  // Depth-first walk with an explicit stack (no recursion depth limit on deep hierarchies).
  std::vector<std::pair<const aiNode*, Affine>> stack;
  std::unordered_set<const aiNode*> seen;
  stack.emplace_back(scene.mRootNode, to_affine(scene.mRootNode->mTransformation));
  while (!stack.empty()) {
    const auto [node, global] = stack.back();
    stack.pop_back();
    if (!seen.insert(node).second) {  // a cycle would make the walk endless
      throw MeshError(source, "not a readable mesh: a node occurs twice in the scene graph");
    }
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned index = node->mMeshes[i];
      if (index >= scene.mNumMeshes || scene.mMeshes[index] == nullptr) {
        throw MeshError(source, "not a readable mesh: a node references mesh " +
                                    std::to_string(index) + " but the scene has " +
                                    std::to_string(scene.mNumMeshes) + " meshes");
      }
      out.push_back({scene.mMeshes[index], global});
    }
    for (unsigned i = node->mNumChildren; i-- > 0;) {
      const aiNode* child = node->mChildren[i];
      if (child != nullptr) stack.emplace_back(child, global * to_affine(child->mTransformation));
    }
  }
  return out;
}

/// Whether the freshly read (not yet validated, so every pointer is checked) scene has at least
/// one face with three or more corners, i.e. something that triangulates.
bool has_polygon(const aiScene& scene) {
  if (scene.mMeshes == nullptr) return false;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr || mesh->mFaces == nullptr) continue;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      if (mesh->mFaces[f].mIndices != nullptr && mesh->mFaces[f].mNumIndices >= 3) return true;
    }
  }
  return false;
}

std::size_t triangle_face_count(const aiMesh& mesh) {
  if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0 || mesh.mFaces == nullptr) return 0;
  std::size_t n = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) n += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
  return n;
}

/// Appends the triangles of one instance. Only vertices that some triangle uses are copied (in
/// order of first use), so vertices of points/lines and unreferenced ones never enter the mesh.
void append_instance(const Instance& inst, const std::string& source, Mesh& out,
                     std::vector<std::uint32_t>& remap) {
  constexpr std::uint32_t unset = std::numeric_limits<std::uint32_t>::max();
  const aiMesh& mesh = *inst.mesh;
  if (triangle_face_count(mesh) == 0) return;
  if (mesh.mVertices == nullptr) {
    throw MeshError(source, "not a readable mesh: a mesh has faces but no vertex positions");
  }
  const Mat3 linear = inst.transform.topLeftCorner<3, 3>();
  const Vec3 shift = inst.transform.topRightCorner<3, 1>();
  // A mirroring node transform turns the winding inside out; swapping two corners restores it.
  const bool mirrored = linear.determinant() < 0;

  remap.assign(mesh.mNumVertices, unset);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines are not collision geometry
    TriangleIndices tri{};
    for (int k = 0; k < 3; ++k) {
      const unsigned v = face.mIndices[k];
      if (v >= mesh.mNumVertices) {
        throw MeshError(source, "triangle " + std::to_string(out.triangles.size()) +
                                    " references vertex " + std::to_string(v) +
                                    " but the mesh has " + std::to_string(mesh.mNumVertices) +
                                    " vertices");
      }
      if (remap[v] == unset) {
        if (out.vertices.size() >= unset) {
          throw MeshError(source, "has more vertices than 32-bit indices can address");
        }
        remap[v] = static_cast<std::uint32_t>(out.vertices.size());
        const aiVector3D& p = mesh.mVertices[v];
        out.vertices.push_back(linear * Vec3(p.x, p.y, p.z) + shift);
      }
      tri[k] = remap[v];
    }
    if (mirrored) std::swap(tri[1], tri[2]);
    out.triangles.push_back(tri);
  }
}

/// assimp's OFF reader trusts the counts in the header and allocates for them before reading any
/// vertex: a 309-byte file announcing 353535235358 vertices (assimp-testmodels'
/// invalid/OutOfMemory.off) makes it allocate and zero about 16 GB. A file in the OFF text format
/// (first token "OFF", "COFF", "NOFF", "STOFF", ...) whose header announces more vertices and
/// faces than its size can hold (at least 6 bytes per vertex "0 0 0\n" and 2 per face) is refused
/// before assimp sees it. Returns the problem, or an empty string when the file is plausible or
/// not OFF at all.
std::string implausible_off_header(std::string_view head, std::uintmax_t file_size) {
  const char* buffer = head.data();
  const std::size_t n = head.size();
  std::size_t i = 0;
  auto space = [&](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  auto skip_blanks_and_comments = [&] {
    while (i < n) {
      if (space(buffer[i])) {
        ++i;
      } else if (buffer[i] == '#') {
        while (i < n && buffer[i] != '\n') ++i;
      } else {
        break;
      }
    }
  };
  skip_blanks_and_comments();
  const std::size_t token_start = i;
  while (i < n && !space(buffer[i]) && buffer[i] != '#') ++i;
  const std::string_view token(buffer + token_start, i - token_start);
  if (token.size() < 3 || token.size() > 8) return {};
  // The OFF keyword: optional prefix letters ST, C, N, 4, n, then "OFF".
  const std::string_view tail = token.substr(token.size() - 3);
  if ((tail[0] | 0x20) != 'o' || (tail[1] | 0x20) != 'f' || (tail[2] | 0x20) != 'f') return {};
  if (token.substr(0, token.size() - 3).find_first_not_of("STCN4n") != std::string_view::npos) {
    return {};
  }
  auto count = [&](std::uint64_t& value) {
    skip_blanks_and_comments();
    if (i >= n || buffer[i] < '0' || buffer[i] > '9') return false;
    value = 0;
    while (i < n && buffer[i] >= '0' && buffer[i] <= '9') {
      value = std::min<std::uint64_t>(value * 10 + static_cast<unsigned>(buffer[i] - '0'),
                                      std::uint64_t{1} << 60);
      ++i;
    }
    return true;
  };
  std::uint64_t vertices = 0;
  std::uint64_t faces = 0;
  if (!count(vertices) || !count(faces)) return {};  // e.g. "OFF BINARY": not checked here
  if (vertices * 6 + faces * 2 <= file_size) return {};
  return "the OFF header announces " + std::to_string(vertices) + " vertices and " +
         std::to_string(faces) + " faces but the file has only " + std::to_string(file_size) +
         " bytes";
}

/// assimp's PLY reader never returns when the file ends inside the header: at the end of the
/// file it keeps parsing the last header line again (appending the same "property" over and over,
/// so memory grows as well). A 60-byte "ply\nformat ascii 1.0\nelement vertex 3\n" is enough. A
/// file that assimp would read as PLY (it starts with "ply", in any case) must therefore have the
/// line assimp ends the header on: "end_header" at the start of a line (after a '\n': assimp
/// skips from any other line end to the next '\n') and optional blanks, followed by a blank, a
/// line end or the end of the file. The scan stops there, so only a broken file is read to its end.
/// Returns the problem, or an empty string when the header is complete or the file is not PLY.
std::string unterminated_ply_header(const std::filesystem::path& path, std::string_view head) {
  if (head.size() < 3 || (head[0] | 0x20) != 'p' || (head[1] | 0x20) != 'l' ||
      (head[2] | 0x20) != 'y') {
    return {};
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return {};  // assimp will report it
  constexpr std::string_view token = "end_header";
  enum class Mode { Blanks, Token, Rest } mode = Mode::Blanks;
  std::size_t matched = 0;
  bool found = false;
  std::array<char, 16384> chunk{};
  std::size_t n = 0;
  while (!found && (n = std::fread(chunk.data(), 1, chunk.size(), file)) > 0) {
    for (std::size_t i = 0; i < n && !found; ++i) {
      const char c = chunk[i];
      const bool blank = c == ' ' || c == '\t';
      if (mode == Mode::Token && matched == token.size() &&
          (blank || c == '\n' || c == '\r' || c == '\0' || c == '\f')) {
        found = true;
      } else if (c == '\n') {
        mode = Mode::Blanks;
        matched = 0;
      } else if (mode == Mode::Blanks && blank) {
        // leading blanks are skipped
      } else if (mode != Mode::Rest && matched < token.size() && c == token[matched]) {
        mode = Mode::Token;
        ++matched;
      } else {
        mode = Mode::Rest;
      }
    }
  }
  std::fclose(file);
  if (found || (mode == Mode::Token && matched == token.size())) return {};
  return "the PLY header has no end_header line";
}

/// How many floats lie between a and b (0 when equal; -0 and +0 are equal), both finite.
std::int64_t float_steps(float a, float b) {
  const auto ordered = [](float x) {
    const auto bits = std::bit_cast<std::int32_t>(x);
    return bits >= 0 ? std::int64_t{bits} : -std::int64_t{bits & 0x7FFFFFFF};
  };
  return std::abs(ordered(a) - ordered(b));
}

/// The float nearest to x, infinity beyond float's range (where a cast would be undefined).
float round_to_float(double x) {
  constexpr double overflow = 0x1.ffffffp127;  // halfway between FLT_MAX and 2^128: rounds up
  if (std::abs(x) >= overflow) {
    return x > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(x);
}

/// A re-read coordinate stands for assimp's float of the same vertex when, rounded to float, it
/// lies at most this many floats away. assimp's text-to-float conversion is not correctly
/// rounded: on 3.6 million numbers printed with %.9g, %.12g and %.17g over every magnitude a
/// float holds (1e-37 .. 1e38), 21 % were 1 float and 0.13 % 2 floats from the nearest float,
/// none further. Twice that bound still fails a re-reading out of step with assimp (another
/// vertex, another property, a misread token), whose values differ by far more; whatever passes
/// is at most 4 floats from assimp's value for that vertex.
constexpr std::int64_t kFloatStepsTolerated = 4;

/// The mesh from assimp's freshly read, validated and not post-processed scene of an OFF or PLY
/// file, with the file's own coordinates (`exact`, in file order) in place of assimp's floats;
/// std::nullopt, so that assimp's floats are used, unless the scene is the single untransformed
/// mesh those readers build, with one vertex per re-read vertex and every coordinate in agreement
/// (kFloatStepsTolerated). The polygons are assimp's, triangulated and joined like OBJ's.
std::optional<Mesh> mesh_with_exact_coordinates(const aiScene& scene, std::vector<Vec3> exact,
                                                const std::string& source) {
  const std::vector<Instance> instances = collect_instances(scene, source);
  if (instances.size() != 1 || instances[0].transform != Affine::Identity()) return std::nullopt;
  const aiMesh& mesh = *instances[0].mesh;
  if (mesh.mVertices == nullptr || mesh.mFaces == nullptr || mesh.mNumVertices != exact.size()) {
    return std::nullopt;
  }
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const aiVector3D& theirs = mesh.mVertices[i];
    for (int k = 0; k < 3; ++k) {
      const float f = theirs[static_cast<unsigned>(k)];
      const double d = exact[i][k];
      // Beyond float's range assimp has an infinity: only the same infinity pairs with it.
      const float rounded = round_to_float(d);
      const bool agree = std::isfinite(f) && std::isfinite(rounded)
                             ? float_steps(rounded, f) <= kFloatStepsTolerated
                             : rounded == f;
      if (!agree) return std::nullopt;
    }
  }
  detail::PolygonSoup soup;
  soup.points = std::move(exact);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices > 0 && face.mIndices == nullptr) return std::nullopt;
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices) return std::nullopt;
      soup.corners.push_back(face.mIndices[k]);
    }
    soup.corner_counts.push_back(face.mNumIndices);
  }
  return detail::soup_to_mesh(soup, source);
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  const std::string source = path.string();

  if (const std::string problem = file_problem(path); !problem.empty()) {
    throw MeshError(source, problem);
  }
  std::error_code ec;
  // A saved Model (bvh.hpp): its mesh, exactly as it was saved.
  if (is_model_path(path)) return Model::load(path).mesh();
  // The first bytes, for the checks assimp does not make (and a clear message when unreadable).
  std::array<char, 4096> head{};
  std::size_t head_size = 0;
  if (std::FILE* file = std::fopen(path.c_str(), "rb"); file != nullptr) {
    head_size = std::fread(head.data(), 1, head.size(), file);
    std::fclose(file);
  } else {
    throw MeshError(source, "cannot be opened: " + printable_line(std::strerror(errno)));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshError(source, "cannot be accessed: " + printable_line(ec.message()));
  if (size == 0) throw MeshError(source, "not a readable mesh: the file is empty");
  if (const std::string problem =
          implausible_off_header(std::string_view(head.data(), head_size), size);
      !problem.empty()) {
    throw MeshError(source, "not a readable mesh: " + problem);
  }
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c | 0x20);
  // Binary STL is read natively (stl_binary.hpp), for the files assimp's STL reader would take as
  // binary (its extension; its size rule).
  if (ext == ".stl" && detail::is_binary_stl(std::string_view(head.data(), head_size), size)) {
    return detail::read_binary_stl(path, source);
  }
  // The whole text, for assimp's OFF reader's check and for the coordinates of OFF and PLY. The
  // OFF reader gets a file by extension, or by content starting with "off" (unless .stl).
  const detail::CoordinateFormat coordinates = detail::coordinate_format(path);
  const bool off_content = head_size >= 3 && (head[0] | 0x20) == 'o' && (head[1] | 0x20) == 'f' &&
                           (head[2] | 0x20) == 'f';
  const bool off_reader = ext == ".off" || (off_content && ext != ".stl");
  // assimp's PLY reader gets a file by extension, or by content starting with "ply" when no
  // reader of its extension takes it.
  const bool ply_content = head_size >= 3 && (head[0] | 0x20) == 'p' && (head[1] | 0x20) == 'l' &&
                           (head[2] | 0x20) == 'y';
  const bool ply_reader = ext == ".ply" || (ply_content && !off_reader && ext != ".stl" &&
                                            detail::text_format(path) != detail::TextFormat::Obj);
  if (const std::string problem =
          unterminated_ply_header(path, std::string_view(head.data(), head_size));
      !problem.empty()) {
    throw MeshError(source, "not a readable mesh: " + problem);
  }
  std::string text;
  if (off_reader || ply_reader || coordinates != detail::CoordinateFormat::None) {
    text = detail::read_whole_file(path, source);
  }
  if (off_reader) {
    if (const std::string problem = detail::unsafe_off_body(text, size); !problem.empty()) {
      throw MeshError(source, "not a readable mesh: " + problem);
    }
  }
  if (ply_reader) {
    if (const std::string problem = detail::unsafe_ply_layout(text); !problem.empty()) {
      throw MeshError(source, "not a readable mesh: " + problem);
    }
  }

  // OBJ is read in double precision; assimp (single precision) reads the rest.
  if (detail::text_format(path) == detail::TextFormat::Obj) {
    return detail::soup_to_mesh(detail::read_obj(path, source), source);
  }

  Assimp::Importer importer;
  // Drop every vertex attribute but the position before vertices are joined, so that vertices
  // that differ only in normal, texture coordinate or colour (e.g. every corner of an STL cube)
  // become one. The other components are dropped to save memory.
  importer.SetPropertyInteger(
      AI_CONFIG_PP_RVC_FLAGS,
      aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS);
  // Some importers invent a mesh that draws the skeleton when a file has none (BVH, ...): that is
  // not geometry of the file.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  constexpr unsigned flags = aiProcess_ValidateDataStructure | aiProcess_RemoveComponent |
                             aiProcess_Triangulate | aiProcess_SortByPType |
                             aiProcess_JoinIdenticalVertices;

  // Read without post-processing first: a file of points or lines only is reported as such here,
  // before assimp's validation would reject its face-less meshes with a less helpful message.
  // Then validate (which guards the other steps against malformed loader output) and post-process.
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(source, 0);
    if (scene != nullptr) {
      if (!has_polygon(*scene)) throw MeshError(source, "contains no triangles");
      // OFF and PLY: the file's own coordinates when they can be paired with assimp's vertices
      // (exact_coordinates.hpp); otherwise, and for every other format, assimp's floats.
      std::optional<std::vector<Vec3>> exact;
      if (coordinates == detail::CoordinateFormat::Off) exact = detail::off_coordinates(text);
      if (coordinates == detail::CoordinateFormat::Ply) exact = detail::ply_coordinates(text);
      if (exact) {
        std::string{}.swap(text);
        scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
        if (scene != nullptr) {
          if (std::optional<Mesh> mesh =
                  mesh_with_exact_coordinates(*scene, std::move(*exact), source)) {
            return std::move(*mesh);
          }
        }
      }
      std::string{}.swap(text);
      if (scene != nullptr) scene = importer.ApplyPostProcessing(flags);
    }
  } catch (const MeshError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw MeshError(source, "not a readable mesh: out of memory while reading it");
  } catch (const std::exception& e) {
    throw MeshError(source, "not a readable mesh: " + printable_line(e.what()));
  }
  if (scene == nullptr) {
    std::string why = printable_line(importer.GetErrorString());
    if (why.empty()) why = "assimp gave no reason";
    throw MeshError(source, "not a readable mesh: " + why);
  }

  const std::vector<Instance> instances = collect_instances(*scene, source);
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  for (const Instance& inst : instances) {
    const std::size_t n = triangle_face_count(*inst.mesh);
    if (n == 0) continue;
    triangles += n;
    vertices += inst.mesh->mNumVertices;
  }
  if (triangles == 0) throw MeshError(source, "contains no triangles");

  Mesh mesh;
  mesh.triangles.reserve(triangles);
  mesh.vertices.reserve(std::min<std::size_t>(vertices, std::numeric_limits<std::uint32_t>::max()));
  std::vector<std::uint32_t> remap;
  std::size_t used = 0;
  for (const Instance& inst : instances) {
    const std::size_t before = mesh.triangles.size();
    append_instance(inst, source, mesh, remap);
    used += mesh.triangles.size() > before ? 1 : 0;
  }
  importer.FreeScene();

  validate_mesh(mesh, source);
  if (used > 1) detail::join_identical_positions(mesh);
  return mesh;
}

}  // namespace antcd
