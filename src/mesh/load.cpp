// load_mesh: reads any mesh file assimp understands into an antcd::Mesh; OBJ is read in double
// precision instead (polygon_soup.hpp, load_obj.cpp), the other formats through assimp.
//
// Every call uses its own Assimp::Importer, so concurrent loads share no state. antcd never
// creates assimp's DefaultLogger (a process-wide object): while no logger exists assimp logs into
// its NullLogger, so loading prints nothing. The one exception seen over all of assimp-testmodels:
// the OpenDDL parser inside the OpenGEX reader writes "nullptr returned by creating DDLNode." to
// stderr for OpenGEX/empty_camera.ogex, past assimp's logger.
#include <antcd/mesh.hpp>

#include "mesh/polygon_soup.hpp"

#include <assimp/config.h>
#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_set>
#include <utility>
#include <vector>

namespace antcd {
namespace {

using detail::one_line;
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

/// assimp 5.2's OFF reader drops a face line whose corner count is 0 or above 9 by decrementing
/// the mesh's face count, without bound: with more such lines than the header has faces the count
/// wraps around to about 4 billion and assimp reads far past its face array (a crash found by
/// fuzzing: "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n0\n3 0 1 2\n"). Its counts are also read from
/// files without the OFF keyword, which implausible_off_header does not see. This walks a file
/// the OFF reader would get (extension .off, or content starting with "off") the way that reader
/// does: its header tokens, then one line per vertex, then face lines until the header's count of
/// faces is read. Returns the problem, or an empty string.
std::string unsafe_off_body(const std::filesystem::path& path, std::string_view head,
                            std::uintmax_t file_size) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c | 0x20);
  const bool off_content = head.size() >= 3 && (head[0] | 0x20) == 'o' && (head[1] | 0x20) == 'f' &&
                           (head[2] | 0x20) == 'f';
  if (ext != ".off" && (!off_content || ext == ".stl")) return {};
  std::string text;
  {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return {};  // assimp will report it
    std::array<char, 16384> chunk{};
    std::size_t n = 0;
    while ((n = std::fread(chunk.data(), 1, chunk.size(), file)) > 0) text.append(chunk.data(), n);
    std::fclose(file);
  }
  text.push_back('\0');  // as assimp's TextFileToBuffer
  const char* p = text.data();
  const char* const end = p + text.size();
  const auto line_end = [](char c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; };
  const auto skip_spaces_and_line_ends = [&] {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
  };
  const auto next_token = [&] {  // blanks, line ends and '#' comment lines
    skip_spaces_and_line_ends();
    while (p < end && (*p == '#' || *p == '\n' || *p == '\r')) {
      while (*p != '\r' && *p != '\n' && *p != '\0') ++p;
      while (*p == '\r' || *p == '\n') ++p;
      skip_spaces_and_line_ends();
    }
  };
  const auto number = [&] {  // assimp's strtoul10, wrapping like it
    std::uint32_t value = 0;
    while (*p >= '0' && *p <= '9') value = value * 10 + static_cast<std::uint32_t>(*p++ - '0');
    return value;
  };
  const auto next_line = [&] {  // assimp's GetNextLine: lines of at most 4096 characters
    if (*p == '\0') return false;
    for (std::size_t k = 0; k < 4096 && !line_end(*p); ++k) ++p;
    while (line_end(*p) && *p != '\0') ++p;
    return true;
  };

  next_token();
  bool dimension = false;
  if (p + 2 < end && p[0] == 'S' && p[1] == 'T') p += 2;
  if (p + 1 < end && p[0] == 'C') ++p;
  if (p + 1 < end && p[0] == 'N') ++p;
  if (p + 1 < end && p[0] == '4') ++p;
  if (p + 1 < end && p[0] == 'n') {
    dimension = true;
    ++p;
  }
  if (p + 3 < end && p[0] == 'O' && p[1] == 'F' && p[2] == 'F') {
    p += 3;
    next_token();
  } else {
    next_token();
    if (p + 1 >= end || *p < '0' || *p > '9') return {};  // assimp: "Header is invalid"
  }
  if (dimension) {
    if (number() > 3) return {};  // assimp refuses more than 3 coordinates
    next_token();
  }
  next_token();
  const std::uint32_t vertices = number();
  next_token();
  const std::uint32_t faces = number();
  next_token();
  (void)number();  // edges
  next_token();
  if (vertices == 0 || faces == 0) return {};  // assimp refuses these
  if (std::uint64_t{vertices} * 6 + std::uint64_t{faces} * 2 > file_size) {
    return "the OFF header announces " + std::to_string(vertices) + " vertices and " +
           std::to_string(faces) + " faces but the file has only " + std::to_string(file_size) +
           " bytes";
  }
  for (std::uint32_t i = 0; i < vertices && next_line(); ++i) {
  }
  std::uint64_t skipped = 0;
  for (std::uint32_t read = 0; read < faces;) {
    const char* line = p;
    if (!next_line()) break;
    while (*line == ' ' || *line == '\t') ++line;
    std::uint32_t corners = 0;
    while (*line >= '0' && *line <= '9') {
      corners = corners * 10 + static_cast<std::uint32_t>(*line++ - '0');
    }
    if (corners == 0 || corners > 9) {
      if (++skipped > faces) {
        return "more face lines with 0 or over 9 corners than faces in the OFF header (" +
               std::to_string(faces) + ")";
      }
    } else {
      ++read;
    }
  }
  return {};
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  const std::string source = path.string();

  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw MeshError(source, "no such file");
  }
  if (ec) throw MeshError(source, "cannot be accessed: " + one_line(ec.message()));
  if (status.type() == std::filesystem::file_type::directory) {
    throw MeshError(source, "is a directory, not a mesh file");
  }
  // Devices, FIFOs and sockets could block or never end.
  if (status.type() != std::filesystem::file_type::regular) {
    throw MeshError(source, "is not a regular file");
  }
  // The first bytes, for the checks assimp does not make (and a clear message when unreadable).
  std::array<char, 4096> head{};
  std::size_t head_size = 0;
  if (std::FILE* file = std::fopen(path.c_str(), "rb"); file != nullptr) {
    head_size = std::fread(head.data(), 1, head.size(), file);
    std::fclose(file);
  } else {
    throw MeshError(source, "cannot be opened: " + one_line(std::strerror(errno)));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshError(source, "cannot be accessed: " + one_line(ec.message()));
  if (size == 0) throw MeshError(source, "not a readable mesh: the file is empty");
  if (const std::string problem =
          implausible_off_header(std::string_view(head.data(), head_size), size);
      !problem.empty()) {
    throw MeshError(source, "not a readable mesh: " + problem);
  }
  if (const std::string problem =
          unsafe_off_body(path, std::string_view(head.data(), head_size), size);
      !problem.empty()) {
    throw MeshError(source, "not a readable mesh: " + problem);
  }
  if (const std::string problem =
          unterminated_ply_header(path, std::string_view(head.data(), head_size));
      !problem.empty()) {
    throw MeshError(source, "not a readable mesh: " + problem);
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
      scene = importer.ApplyPostProcessing(flags);
    }
  } catch (const MeshError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw MeshError(source, "not a readable mesh: out of memory while reading it");
  } catch (const std::exception& e) {
    throw MeshError(source, "not a readable mesh: " + one_line(e.what()));
  }
  if (scene == nullptr) {
    std::string why = one_line(importer.GetErrorString());
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
