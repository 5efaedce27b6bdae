#include "view_page.hpp"

#include <antcd/collide.hpp>
#include <antcd/file.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <type_traits>
#include <unordered_map>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

using json = nlohmann::json;

// Appends little-endian 4-byte values to the blob and returns [byte offset, count] for the JSON.
class BlobWriter {
 public:
  explicit BlobWriter(std::string& blob) : blob_(blob) {}

  json floats(const std::vector<float>& values) { return append(values.data(), values.size()); }
  json uints(const std::vector<std::uint32_t>& values) {
    return append(values.data(), values.size());
  }
  /// float64 arrays start on a 4-byte boundary only: the page copies them out (data.js).
  json doubles(const std::vector<double>& values) { return append(values.data(), values.size()); }

 private:
  template <typename T>
  json append(const T* data, std::size_t count) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 8);
    using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    const std::size_t offset = blob_.size();  // always a multiple of 4
    blob_.resize(offset + count * sizeof(T));
    for (std::size_t i = 0; i < count; ++i) {
      Bits bits = 0;
      std::memcpy(&bits, data + i, sizeof(T));
      for (std::size_t b = 0; b < sizeof(T); ++b) {
        blob_[offset + i * sizeof(T) + b] = static_cast<char>((bits >> (8 * b)) & 0xFFU);
      }
    }
    return json::array({offset, count});
  }

  std::string& blob_;
};

void append_pose(std::vector<float>& out, const Transform& t) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(t.rotation(r, c)));
  }
  for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(t.translation[k]));
}

// True unless the result names a scene file that exists and is not `scene` (relative names are
// tried against the working folder and against the result's folder, since `antcd run` records
// the path as it was given).
bool recorded_scene_matches(const std::string& recorded, const std::filesystem::path& scene,
                            const std::filesystem::path& result_path) {
  if (recorded.empty()) return true;
  std::vector<std::filesystem::path> candidates{recorded};
  const std::filesystem::path p(recorded);
  if (p.is_relative()) candidates.push_back(result_path.parent_path() / p);
  bool any_exists = false;
  for (const auto& c : candidates) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(c, ec)) continue;
    any_exists = true;
    if (std::filesystem::equivalent(c, scene, ec)) return true;
  }
  return !any_exists;
}

json pack_result(const shared::RunResult& r, const std::filesystem::path& path, const Scene& engine,
                 const std::filesystem::path& scene_path,
                 const std::unordered_map<std::string, std::uint32_t>& index_of, BlobWriter& blob) {
  const SceneDescription& scene = engine.description();
  const std::string src = path.string();
  if (!recorded_scene_matches(r.scene, scene_path, path)) {
    throw UsageError(src + ": a result for another scene ('" + r.scene + "', not '" +
                     scene_path.string() + "')");
  }
  if (!std::isfinite(r.delta) || r.delta < 0) {
    throw UsageError(src + ": delta " + std::to_string(r.delta) + " is not a finite number >= 0");
  }
  json frames = json::array();
  json pairs = json::array();
  json times = json::array();
  json candidates = json::array();
  json tois = json::array();     // continuous results: per frame, each pair's first time of impact
  json touches = json::array();  // and contact point there, in the order of the input pairs
  json self = json::array();     // per frame: [object, triangle pairs (uint32 a, b per pair)]
  bool any_self = false;
  std::set<std::size_t> seen;
  for (const shared::FrameRecord& f : r.frames) {
    if (f.frame >= scene.frames) {
      throw UsageError(src + ": frame " + std::to_string(f.frame) + " out of range (" +
                       scene_path.string() + " has " + std::to_string(scene.frames) + " frames)");
    }
    if (!seen.insert(f.frame).second) {
      throw UsageError(src + ": frame " + std::to_string(f.frame) + " listed twice");
    }
    json fp = json::array();
    for (const auto& [a, b] : f.pairs) {
      const auto ia = index_of.find(a);
      const auto ib = index_of.find(b);
      if (ia == index_of.end() || ib == index_of.end()) {
        throw UsageError(src + ": frame " + std::to_string(f.frame) + ": pair (" + a + ", " + b +
                         "): no object '" + (ia == index_of.end() ? a : b) + "' in " +
                         scene_path.string());
      }
      fp.push_back(
          json::array({std::min(ia->second, ib->second), std::max(ia->second, ib->second)}));
    }
    json fs = json::array();
    for (const auto& [name, triangles] : f.self_pairs) {
      const auto it = index_of.find(name);
      if (it == index_of.end()) {
        throw UsageError(src + ": frame " + std::to_string(f.frame) + ": self pair of '" + name +
                         "': no such object in " + scene_path.string());
      }
      const std::size_t count = engine.model_of(it->second).mesh().triangles.size();
      std::vector<std::uint32_t> flat;
      flat.reserve(triangles.size() * 2);
      for (const auto& t : triangles) {
        if (t[0] >= count || t[1] >= count) {
          throw UsageError(src + ": frame " + std::to_string(f.frame) + ": self pair of '" + name +
                           "': triangle " + std::to_string(std::max(t[0], t[1])) +
                           " out of range (its mesh has " + std::to_string(count) + ")");
        }
        flat.insert(flat.end(), t.begin(), t.end());
      }
      fs.push_back(json::array({it->second, blob.uints(flat)}));
      any_self = true;
    }
    self.push_back(std::move(fs));
    frames.push_back(f.frame);
    pairs.push_back(std::move(fp));
    times.push_back(f.time_ms);
    candidates.push_back(f.candidates.size());
    if (r.continuous) {
      if (!f.toi || !f.contact_points) {
        throw UsageError(src + ": frame " + std::to_string(f.frame) +
                         ": a continuous result without 'toi' and 'contact_points'");
      }
      tois.push_back(*f.toi);
      touches.push_back(*f.contact_points);
    }
  }
  json out{{"label", path.filename().string()},
           {"method", r.method},
           {"frames", frames},
           {"pairs", pairs},
           {"time_ms", times},
           {"candidates", candidates},
           {"delta", r.delta},
           {"seed", r.seed}};
  if (any_self) out["self_triangles"] = std::move(self);
  if (r.continuous) {
    out["toi"] = std::move(tois);
    out["touch_points"] = std::move(touches);
  }
  return out;
}

// The scaled vertices of deforming object `o` at `frame` (model frame), as the Scene refits them.
std::vector<Vec3> scaled_frame(const SceneObject& o, std::size_t frame) {
  const std::span<const Vec3> v = o.vertex_frames->frame(frame);
  std::vector<Vec3> out(v.begin(), v.end());
  if (o.scale != 1) {
    for (Vec3& p : out) p *= o.scale;
  }
  return out;
}

// Exact contact points (world frame) of every pair of distinct objects some result reports, on
// every frame a result covers: where the surfaces of the pair really touch (none for a false
// alarm). At most `per_pair` per pair; δ as in the reference result. A deforming object is
// tested with its vertices of that frame (a copy of its Model refitted, as Scene::run_frame
// does); self pairs get no points here (their triangle pairs are in the result's
// "self_triangles").
json pack_contacts(const Scene& scene, const json& results, double delta, std::size_t per_pair,
                   BlobWriter& blob) {
  std::map<std::size_t, std::set<std::pair<std::uint32_t, std::uint32_t>>> pairs_at;
  for (const json& r : results) {
    for (std::size_t k = 0; k < r["frames"].size(); ++k) {
      auto& set = pairs_at[r["frames"][k].get<std::size_t>()];
      for (const json& p : r["pairs"][k]) {
        if (p[0] != p[1]) set.emplace(p[0].get<std::uint32_t>(), p[1].get<std::uint32_t>());
      }
    }
  }
  const auto& objects = scene.description().objects;
  CollisionRequest request;
  request.delta = delta;
  request.all_contacts = true;
  request.max_contacts = per_pair;
  CollisionResult hit;
  json frames = json::array();
  json points = json::array();
  for (const auto& [frame, pairs] : pairs_at) {
    std::map<std::uint32_t, std::unique_ptr<Model>> refitted;  // deforming objects of this frame
    const auto model = [&](std::uint32_t i) -> const Model& {
      if (!objects[i].deforming()) return scene.model_of(i);
      auto& m = refitted[i];
      if (!m) {
        m = std::make_unique<Model>(scene.model_of(i));
        m->refit(scaled_frame(objects[i], frame));
      }
      return *m;
    };
    std::vector<float> xyz;
    for (const auto& [i, j] : pairs) {
      collide(model(i), objects[i].pose(frame), model(j), objects[j].pose(frame), request, hit);
      for (const Contact& c : hit.contacts) {
        for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<float>(c.point[k]));
      }
    }
    if (xyz.empty()) continue;
    frames.push_back(frame);
    points.push_back(blob.floats(xyz));
  }
  return json{{"frames", frames}, {"points", points}, {"per_pair", per_pair}, {"delta", delta}};
}

}  // namespace

ViewResult load_view_result(const std::filesystem::path& path) {
  return {path, shared::parse_run_result(read_file(path), path.string())};
}

ViewPayload build_view_payload(const ViewInputs& inputs) {
  if (inputs.results.size() > 2) {
    throw UsageError("--result given " + std::to_string(inputs.results.size()) +
                     " times: the viewer shows one result or compares two");
  }
  // Loads every mesh once per (file, scale) and builds the models the contacts are computed on.
  std::unique_ptr<Scene> engine;
  try {
    engine = std::make_unique<Scene>(load_scene(inputs.scene));
  } catch (const Error& e) {
    // Parse errors name the scene file already; mesh errors name the object and the mesh.
    const std::string what = e.what();
    if (what.starts_with(inputs.scene.string() + ":")) throw;
    throw UsageError(inputs.scene.string() + ": " + what);
  }
  const SceneDescription& scene = engine->description();
  ViewPayload out;
  out.title = inputs.scene.filename().string();
  out.objects = scene.objects.size();
  out.frames = scene.frames;
  BlobWriter blob(out.blob);

  // One mesh entry per model (distinct file and scale, scale applied); colours follow the file,
  // so the same part at two scales has one colour.
  json meshes = json::array();
  json objects = json::array();
  std::map<const Model*, std::size_t> mesh_index;
  std::map<std::string, std::size_t> colour_index;
  std::unordered_map<std::string, std::uint32_t> index_of;
  std::size_t vertex_bytes = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    index_of.emplace(o.name, static_cast<std::uint32_t>(i));
    const Model& model = engine->model_of(i);
    auto it = mesh_index.find(&model);
    if (it == mesh_index.end()) {
      const Mesh& mesh = model.mesh();
      std::vector<float> positions;
      positions.reserve(mesh.vertices.size() * 3);
      for (const Vec3& v : mesh.vertices) {
        for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(v[k]));
      }
      std::vector<std::uint32_t> indices;
      indices.reserve(mesh.triangles.size() * 3);
      for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
      const auto colour =
          colour_index.emplace(o.mesh.lexically_normal().string(), colour_index.size())
              .first->second;
      meshes.push_back(json{{"file", o.mesh_text},
                            {"scale", o.scale},
                            {"colour", colour},
                            {"vertices", mesh.vertices.size()},
                            {"triangles", mesh.triangles.size()},
                            {"positions", blob.floats(positions)},
                            {"indices", blob.uints(indices)}});
      if (inputs.live) {
        std::vector<double> exact;
        exact.reserve(mesh.vertices.size() * 3);
        for (const Vec3& v : mesh.vertices) exact.insert(exact.end(), v.data(), v.data() + 3);
        meshes.back()["positions64"] = blob.doubles(exact);
      }
      it = mesh_index.emplace(&model, meshes.size() - 1).first;
    }
    std::vector<float> poses;
    poses.reserve(o.poses.size() * 12);
    for (const Transform& t : o.poses) append_pose(poses, t);
    objects.push_back(json{{"name", o.name}, {"mesh", it->second}, {"poses", blob.floats(poses)}});
    if (o.self_collision) objects.back()["self_collision"] = true;
    if (o.deforming()) {
      // Every frame's vertices (scaled, model frame), as the Scene refits the object with them.
      const std::size_t values = scene.frames * model.mesh().vertices.size() * 3;
      vertex_bytes += values * (inputs.live ? 8 : 4);
      if (vertex_bytes > kMaxVertexFrameBytes) {
        throw UsageError(inputs.scene.string() + ": object '" + o.name +
                         "': the deforming objects' vertex frames would take " +
                         std::to_string(vertex_bytes >> 20) + " MiB of the page, more than " +
                         std::to_string(kMaxVertexFrameBytes >> 20) +
                         " MiB (antcd view's limit): view a scene with fewer frames or sheets");
      }
      if (inputs.live) {
        // float64 only (the page's WebAssembly models need them; it rounds its own float32).
        std::vector<double> exact;
        exact.reserve(values);
        for (std::size_t f = 0; f < scene.frames; ++f) {
          for (const Vec3& v : scaled_frame(o, f))
            exact.insert(exact.end(), v.data(), v.data() + 3);
        }
        objects.back()["vertex_frames64"] = blob.doubles(exact);
      } else {
        std::vector<float> rounded;
        rounded.reserve(values);
        for (std::size_t f = 0; f < scene.frames; ++f) {
          for (const Vec3& v : scaled_frame(o, f)) {
            for (int k = 0; k < 3; ++k) rounded.push_back(static_cast<float>(v[k]));
          }
        }
        objects.back()["vertex_frames"] = blob.floats(rounded);
      }
    }
    if (inputs.live) {
      // The same layout as "poses" (rotation row by row, then translation), unrounded.
      std::vector<double> exact;
      exact.reserve(o.poses.size() * 12);
      for (const Transform& t : o.poses) {
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) exact.push_back(t.rotation(r, c));
        }
        exact.insert(exact.end(), t.translation.data(), t.translation.data() + 3);
      }
      objects.back()["poses64"] = blob.doubles(exact);
    }
  }

  json results = json::array();
  for (const ViewResult& r : inputs.results) {
    results.push_back(pack_result(r.run, r.source, *engine, inputs.scene, index_of, blob));
  }

  json root{{"format", "antcd-view/1"}, {"scene", out.title},
            {"frames", scene.frames},   {"colours", colour_index.size()},
            {"meshes", meshes},         {"objects", objects},
            {"results", results}};
  if (inputs.live) root["live"] = true;
  out.live = inputs.live;
  if (inputs.contacts_per_pair > 0 && !inputs.results.empty()) {
    root["contacts"] = pack_contacts(*engine, results, inputs.results.front().run.delta,
                                     inputs.contacts_per_pair, blob);
  }
  root["blob_bytes"] = out.blob.size();
  out.json = root.dump(-1, ' ', false, json::error_handler_t::replace);
  return out;
}

std::filesystem::path locate_viewer_bundle(bool live) {
  std::vector<std::filesystem::path> tried;
  std::error_code ec;
  const char* variable = live ? "ANTCD_LIVE_JS" : "ANTCD_VIEWER_JS";
  const char* file = live ? "antcd-live.js" : "antcd-viewer.js";
  if (const char* env = std::getenv(variable); env != nullptr && *env != '\0') {
    if (!std::filesystem::is_regular_file(env, ec)) {
      throw UsageError(std::string(variable) + "=" + env + ": no such file (the viewer bundle)");
    }
    return env;
  }
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto dir = exe.parent_path();
    tried.push_back(dir.parent_path() / "share" / "antcd" / file);       // installed
    tried.push_back(dir.parent_path().parent_path() / "viewer" / file);  // build tree
  }
  for (const auto& p : tried) {
    if (std::filesystem::is_regular_file(p, ec)) return p;
  }
  std::string where;
  for (const auto& p : tried) where += (where.empty() ? "" : ", ") + p.string();
  throw UsageError(std::string(live ? "the live viewer page" : "the browser viewer") +
                   " is not built (looked for " + where +
                   "): it is bundled at build time from viewer/ with npm; install node and npm" +
                   (live ? " and Emscripten" : "") +
                   " (scripts/install-deps.sh does) and re-run cmake and the build");
}

ViewPayload write_view_file(const ViewInputs& inputs, const std::filesystem::path& out) {
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec)) {
    throw UsageError(out.string() + ": is a folder, expected an HTML file name");
  }
  // Inputs first, so that every input error is reported even where the viewer is not built.
  ViewPayload payload = build_view_payload(inputs);
  const std::string bundle = read_file(locate_viewer_bundle(inputs.live));
  write_file_atomic(out, render_page(payload, bundle, PageMode::SelfContained));
  payload.blob.clear();
  payload.json.clear();
  return payload;
}

std::string base64_encode(const std::string& bytes) {
  static constexpr char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  const auto byte = [&](std::size_t k) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k]));
  };
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (byte(i) << 16) | (byte(i + 1) << 8) | byte(i + 2);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += alphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t v = (byte(i) << 16) | (rest == 2 ? byte(i + 1) << 8 : 0);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += rest == 2 ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

namespace {

// Inside a <script> element only "</script" and "<!--" can end or confuse the element; in JSON
// text '<' only occurs inside strings, where \u003c means the same character.
std::string json_for_script(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string render_page(const ViewPayload& payload, const std::string& bundle_js, PageMode mode) {
  // The bundle must not close its own element early (viewer/build.mjs checks this too).
  std::string lowered = bundle_js;
  for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lowered.find("</script") != std::string::npos) {
    throw UsageError("the viewer bundle contains '</script' and cannot be inlined");
  }
  const bool served = mode == PageMode::Served;
  std::string page;
  page.reserve(bundle_js.size() + payload.json.size() + payload.blob.size() * 4 / 3 + 4096);
  page +=
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
      "script-src 'unsafe-inline'";
  if (payload.live) page += " 'wasm-unsafe-eval'";
  page += "; style-src 'unsafe-inline'; img-src data: blob:; connect-src ";
  page += served ? "'self'" : "'none'";
  page += "\">\n<title>antcd view: " + html_escape(payload.title) + "</title>\n</head>\n<body>\n";
  page += "<div id=\"antcd-viewer\"></div>\n";
  page += "<script type=\"application/json\" id=\"antcd-view-data\">" +
          json_for_script(payload.json) + "</script>\n";
  if (served) {
    page +=
        "<script type=\"application/octet-stream\" id=\"antcd-view-blob\" "
        "data-src=\"antcd-view.bin\"></script>\n";
  } else {
    page += "<script type=\"application/octet-stream\" id=\"antcd-view-blob\">";
    page += base64_encode(payload.blob);
    page += "</script>\n";
  }
  page += "<script>\n" + bundle_js + "\n</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace antcd::cli
