// The antcd-scene/1 file format: parsing with one clear error per violation, and writing.
#include <antcd/file.hpp>
#include <antcd/scene.hpp>
#include <antcd/tolerances.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

namespace antcd {

namespace {

using nlohmann::json;

constexpr std::string_view kFormat = "antcd-scene/1";

class Parser {
 public:
  static constexpr int kMaxNesting = 32;

  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    // Names and keys come from the file and may hold control characters ("a\nb" is valid JSON):
    // they are escaped so that the message stays one line.
    const std::string text = (where.empty() ? "" : where + ": ") + problem;
    std::string message = source_ + ": ";
    message.reserve(message.size() + text.size());
    for (const char c : text) {
      const auto u = static_cast<unsigned char>(c);
      if (u >= 0x20 && u != 0x7F) {
        message += c;
      } else {
        constexpr char hex[] = "0123456789abcdef";
        message += "\\x";
        message += hex[u >> 4];
        message += hex[u & 0xF];
      }
    }
    throw SceneError(message);
  }

  /// A short, one-line description of a JSON value for messages. json::dump() is avoided for
  /// arrays and objects: it recurses once per nesting level, and a file of a million nested
  /// brackets overflowed the stack.
  static std::string describe(const json& j) {
    if (j.is_array() || j.is_object()) return std::string("(a JSON ") + j.type_name() + ")";
    std::string text = j.dump();
    if (text.size() > 80) text = text.substr(0, 77) + "...";
    return text;
  }

  Scalar number(const json& j, const std::string& where, const std::string& field) const {
    if (!j.is_number()) fail(where, "'" + field + "' must be a number");
    const Scalar v = j.get<Scalar>();
    if (!std::isfinite(v)) fail(where, "'" + field + "' is not finite");
    return v;
  }

  Vec3 vec3(const json& j, const std::string& where, const std::string& field) const {
    if (!j.is_array() || j.size() != 3)
      fail(where, "'" + field + "' must be an array of 3 numbers");
    return {number(j[0], where, field), number(j[1], where, field), number(j[2], where, field)};
  }

  Transform pose(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "a pose must be an object");
    for (const auto& [key, value] : j.items()) {
      if (key != "translation" && key != "rotation_wxyz")
        fail(where, "unknown pose field '" + key + "'");
    }
    Transform t;
    if (j.contains("translation")) t.translation = vec3(j["translation"], where, "translation");
    if (j.contains("rotation_wxyz")) {
      const json& q = j["rotation_wxyz"];
      if (!q.is_array() || q.size() != 4) {
        fail(where, "'rotation_wxyz' must be an array of 4 numbers (w, x, y, z)");
      }
      const Scalar w = number(q[0], where, "rotation_wxyz");
      const Scalar x = number(q[1], where, "rotation_wxyz");
      const Scalar y = number(q[2], where, "rotation_wxyz");
      const Scalar z = number(q[3], where, "rotation_wxyz");
      const Scalar norm = std::sqrt(w * w + x * x + y * y + z * z);
      if (!(std::abs(norm - 1) <= tolerance::kUnitQuaternion)) {
        std::ostringstream msg;
        msg << "quaternion has length " << norm << ", expected 1 (within "
            << tolerance::kUnitQuaternion << ")";
        fail(where, msg.str());
      }
      t.rotation = Quat(w / norm, x / norm, y / norm, z / norm).toRotationMatrix();
    }
    return t;
  }

  SceneDescription scene(std::string_view text, const std::filesystem::path& base_dir) const {
    json root;
    // A scene nests 5 levels deep (objects, object, poses, pose, translation). Deeper nesting is
    // refused as it is read, before a level is allocated: a file of a few MB of brackets would
    // otherwise take gigabytes.
    bool too_deep = false;
    const auto limit_depth = [&too_deep](int depth, json::parse_event_t event, json&) {
      if ((event == json::parse_event_t::object_start ||
           event == json::parse_event_t::array_start) &&
          depth >= kMaxNesting) {
        too_deep = true;
        throw std::length_error("nesting");
      }
      return true;
    };
    try {
      root = json::parse(text.begin(), text.end(), limit_depth);
    } catch (const std::length_error&) {
      if (!too_deep) throw;
      fail("", "nested deeper than " + std::to_string(kMaxNesting) + " levels");
    } catch (const json::exception& e) {  // parse errors, and out_of_range for 1e999
      std::string msg = e.what();
      for (char& c : msg) {
        if (c == '\n') c = ' ';
      }
      fail("", "not valid JSON (" + msg + ")");
    }
    if (!root.is_object()) fail("", "the top level must be a JSON object");
    if (!root.contains("format")) fail("", "missing 'format' (expected \"antcd-scene/1\")");
    if (!root["format"].is_string() || root["format"].get<std::string>() != kFormat) {
      fail("", "unknown format " + describe(root["format"]) + " (expected \"antcd-scene/1\")");
    }
    for (const auto& [key, value] : root.items()) {
      if (key != "format" && key != "frames" && key != "objects") {
        fail("", "unknown field '" + key + "'");
      }
    }
    SceneDescription out;
    if (!root.contains("frames")) fail("", "missing 'frames'");
    const json& frames = root["frames"];
    if (!frames.is_number_integer() || frames.get<std::int64_t>() < 1 ||
        frames.get<std::int64_t>() > 10'000'000) {
      fail("", "'frames' must be an integer from 1 to 10000000");
    }
    out.frames = frames.get<std::size_t>();
    if (!root.contains("objects") || !root["objects"].is_array()) {
      fail("", "missing 'objects' array");
    }
    std::unordered_set<std::string> names;
    std::size_t index = 0;
    for (const json& o : root["objects"]) {
      std::string where = "object " + std::to_string(index);
      if (!o.is_object()) fail(where, "must be a JSON object");
      if (!o.contains("name") || !o["name"].is_string() || o["name"].get<std::string>().empty()) {
        fail(where, "missing or empty 'name'");
      }
      SceneObject obj;
      obj.name = o["name"].get<std::string>();
      where = "object '" + obj.name + "'";
      for (const auto& [key, value] : o.items()) {
        if (key != "name" && key != "mesh" && key != "scale" && key != "poses" &&
            key != "vertex_frames" && key != "self_collision") {
          fail(where, "unknown field '" + key + "'");
        }
      }
      if (!names.insert(obj.name).second) fail(where, "duplicate name");
      if (!o.contains("mesh") || !o["mesh"].is_string() || o["mesh"].get<std::string>().empty()) {
        fail(where, "missing or empty 'mesh'");
      }
      obj.mesh_text = o["mesh"].get<std::string>();
      // "a.obj\u0000b" is valid JSON; the file system would open "a.obj", another file.
      if (obj.mesh_text.find('\0') != std::string::npos) fail(where, "'mesh' holds a NUL byte");
      const std::filesystem::path mesh_path(obj.mesh_text);
      obj.mesh = mesh_path.is_absolute() ? mesh_path : base_dir / mesh_path;
      if (o.contains("vertex_frames")) {
        const json& v = o["vertex_frames"];
        if (!v.is_string() || v.get<std::string>().empty()) {
          fail(where, "'vertex_frames' must be a non-empty file name");
        }
        obj.vertex_file_text = v.get<std::string>();
        if (obj.vertex_file_text.find('\0') != std::string::npos) {
          fail(where, "'vertex_frames' holds a NUL byte");
        }
        const std::filesystem::path vertex_path(obj.vertex_file_text);
        obj.vertex_file = vertex_path.is_absolute() ? vertex_path : base_dir / vertex_path;
      }
      if (o.contains("self_collision")) {
        if (!o["self_collision"].is_boolean())
          fail(where, "'self_collision' must be true or false");
        obj.self_collision = o["self_collision"].get<bool>();
      }
      if (o.contains("scale")) {
        obj.scale = number(o["scale"], where, "scale");
        if (!(obj.scale > 0)) fail(where, "'scale' must be > 0");
      }
      if (!o.contains("poses") || !o["poses"].is_array() || o["poses"].empty()) {
        fail(where, "missing 'poses' (one pose, or one per frame)");
      }
      const json& poses = o["poses"];
      if (poses.size() != 1 && poses.size() != out.frames) {
        fail(where, "has " + std::to_string(poses.size()) + " poses; expected 1 or " +
                        std::to_string(out.frames) + " (frames)");
      }
      obj.poses.reserve(poses.size());
      for (std::size_t k = 0; k < poses.size(); ++k) {
        obj.poses.push_back(pose(poses[k], where + ": pose " + std::to_string(k)));
      }
      out.objects.push_back(std::move(obj));
      ++index;
    }
    if (out.objects.empty()) fail("", "'objects' is empty");
    return out;
  }

 private:
  std::string source_;
};

json vec_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

SceneDescription parse_scene(std::string_view json_text, const std::filesystem::path& base_dir,
                             const std::string& source) {
  return Parser(source).scene(json_text, base_dir);
}

SceneDescription load_scene(const std::filesystem::path& path) {
  std::string text;
  try {
    text = read_file(path);
  } catch (const Error& e) {
    throw SceneError(e.what());
  }
  SceneDescription scene = parse_scene(text, path.parent_path(), path.string());
  load_vertex_frames(scene, path.string());
  return scene;
}

std::string scene_to_json(const SceneDescription& scene) {
  json root;
  root["format"] = kFormat;
  root["frames"] = scene.frames;
  json objects = json::array();
  for (const SceneObject& o : scene.objects) {
    json jo;
    jo["name"] = o.name;
    jo["mesh"] = o.mesh_text.empty() ? o.mesh.generic_string() : o.mesh_text;
    if (o.scale != 1) jo["scale"] = o.scale;
    if (!o.vertex_file_text.empty()) jo["vertex_frames"] = o.vertex_file_text;
    if (o.self_collision) jo["self_collision"] = true;
    json poses = json::array();
    for (const Transform& t : o.poses) {
      const Quat q(t.rotation);
      poses.push_back({{"translation", vec_json(t.translation)},
                       {"rotation_wxyz", json::array({q.w(), q.x(), q.y(), q.z()})}});
    }
    jo["poses"] = std::move(poses);
    objects.push_back(std::move(jo));
  }
  root["objects"] = std::move(objects);
  return root.dump(1);
}

void save_scene(const SceneDescription& scene, const std::filesystem::path& path) {
  write_file_atomic(path, scene_to_json(scene));
}

}  // namespace antcd
