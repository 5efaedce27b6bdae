#include "shared/run_result.hpp"

#include "shared/statistics.hpp"

#include <antcd/distance.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace antcd::shared {

namespace {

using nlohmann::json;

std::vector<NamePair> names_of(const Scene& scene,
                               const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  std::vector<NamePair> out;
  out.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    out.emplace_back(scene.description().objects[i].name, scene.description().objects[j].name);
  }
  return out;
}

json pairs_json(const std::vector<NamePair>& pairs) {
  json out = json::array();
  for (const auto& [a, b] : pairs) out.push_back(json::array({a, b}));
  return out;
}

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw Error(source + ": " + problem);
}

std::vector<NamePair> parse_pairs(const json& j, const std::string& source,
                                  const std::string& where) {
  if (!j.is_array()) fail(source, where + " must be an array of name pairs");
  std::vector<NamePair> out;
  for (const json& p : j) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_string() || !p[1].is_string()) {
      fail(source, where + " must hold pairs of names, e.g. [\"a\", \"b\"]");
    }
    out.emplace_back(p[0].get<std::string>(), p[1].get<std::string>());
  }
  return out;
}

double number(const json& j, const std::string& key, const std::string& source,
              const std::string& where) {
  if (!j.contains(key) || !j[key].is_number()) {
    fail(source, where + "missing number '" + key + "'");
  }
  return j[key].get<double>();
}

/// Limits checked on the text before it is parsed: the format nests 5 levels (the top object,
/// "frames", a frame, "pairs", a pair), and a run of 1000 frames with a few hundred pairs each
/// holds about a million values. The JSON tree costs some 40 bytes a value, so these bound the
/// memory a hostile file can take (a megabyte of '[' would otherwise build a million nested
/// arrays).
constexpr std::size_t kMaxResultNesting = 16;
constexpr std::size_t kMaxResultValues = std::size_t{1} << 24;

/// One pass over the bytes, outside strings: the deepest nesting of arrays and objects, and an
/// upper bound of the values (1 + commas + containers), each refused above its limit.
void check_shape(std::string_view text, const std::string& source) {
  std::size_t depth = 0;
  std::size_t values = 1;
  bool in_string = false;
  bool escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxResultNesting) {
        fail(source, "nested deeper than " + std::to_string(kMaxResultNesting) + " levels");
      }
      ++values;
    } else if (c == ']' || c == '}') {
      depth -= depth > 0 ? 1 : 0;  // unbalanced text is the parser's to report
    } else if (c == ',') {
      ++values;
    }
    if (values > kMaxResultValues) {
      fail(source, "more than " + std::to_string(kMaxResultValues) + " values");
    }
  }
}

// A frame's array of one number per pair (each in [0, 1] if unit_interval).
std::vector<double> per_pair_numbers(const json& j, std::size_t pairs, const std::string& source,
                                     const std::string& where, const std::string& name,
                                     bool unit_interval) {
  if (!j.is_array() || j.size() != pairs) {
    fail(source, where + "'" + name + "' must be an array of one number per pair");
  }
  std::vector<double> out;
  for (const json& x : j) {
    if (!x.is_number()) fail(source, where + "'" + name + "' must hold numbers");
    const double v = x.get<double>();
    if (unit_interval && !(v >= 0 && v <= 1)) {
      fail(source, where + "'" + name + "' must hold numbers in [0, 1]");
    }
    out.push_back(v);
  }
  return out;
}

// Unordered key for a name pair, so that ["a", "b"] and ["b", "a"] compare equal.
NamePair key(const NamePair& p) { return p.first < p.second ? p : NamePair{p.second, p.first}; }

}  // namespace

RunResult run_scene(const Scene& scene, const SceneQuery& query, const std::string& scene_name,
                    const std::function<void(std::size_t, std::size_t)>& progress,
                    std::size_t frame_step, bool memory) {
  if (frame_step < 1) throw Error("frame step must be at least 1");
  if (query.continuous && frame_step != 1) {
    throw Error("a continuous run sweeps from each frame to the next: frame step must be 1");
  }
  RunResult out;
  out.method = std::string(method_name(query.method));
  out.scene = scene_name;
  out.delta = query.delta;
  out.seed = query.seed;
  out.threads = query.threads;
  out.volume = query.volume;
  out.continuous = query.continuous;
  out.build_ms = scene.build_ms();
  const std::size_t frames = scene.description().frames;
  const std::size_t runs = (frames + frame_step - 1) / frame_step;
  out.frames.reserve(runs);
  const bool random = query.method != Method::Exact && query.method != Method::SphereObb;
  if (random) {
    out.verdict = std::string(to_string(query.random.search.verdict));
    out.memory = memory;
    out.leaf_scan = query.random.search.ant.scan_covered_spaces;
  }
  SceneMemory colonies;
  for (std::size_t f = 0; f < frames; f += frame_step) {
    const FrameResult r = scene.run_frame(f, query, random && memory ? &colonies : nullptr);
    FrameRecord rec;
    rec.frame = f;
    rec.pairs = names_of(scene, r.pairs);
    rec.candidates = names_of(scene, r.candidates);
    rec.time_ms = r.time_ms;
    for (const SelfPairs& sp : r.self_pairs) {
      rec.self_pairs.emplace_back(scene.description().objects[sp.object].name, sp.triangles);
    }
    if (random) {
      rec.feature_hits = r.feature_hits;
      if (query.random.count_truth) rec.feature_truth = r.feature_truth;
      rec.evaluations = r.evaluations;
      rec.undecided = names_of(scene, r.undecided);
    }
    if (query.continuous) {
      rec.toi = std::vector<double>(r.toi.begin(), r.toi.end());
      rec.contact_points.emplace();
      for (const Vec3& p : r.contact_points) rec.contact_points->push_back({p.x(), p.y(), p.z()});
    }
    out.total_ms += r.time_ms;
    out.frames.push_back(std::move(rec));
    if (progress) progress(out.frames.size(), runs);
  }
  return out;
}

void add_distances(const Scene& scene, RunResult& result) {
  const auto& objects = scene.description().objects;
  std::map<std::string, std::uint32_t, std::less<>> index;
  for (std::uint32_t i = 0; i < objects.size(); ++i) index.emplace(objects[i].name, i);
  const auto find = [&](const std::string& name) {
    const auto it = index.find(name);
    if (it == index.end()) throw Error("run result names object '" + name + "' not in the scene");
    return it->second;
  };
  for (FrameRecord& f : result.frames) {
    if (f.frame >= scene.description().frames) {
      throw Error("run result has frame " + std::to_string(f.frame) + " beyond the scene's " +
                  std::to_string(scene.description().frames));
    }
    std::vector<double> d;
    d.reserve(f.pairs.size());
    for (const auto& [na, nb] : f.pairs) {
      for (const std::string* name : {&na, &nb}) {
        if (objects[find(*name)].deforming()) {
          throw Error("surface distances are not computed for deforming objects ('" + *name +
                      "' deforms)");
        }
      }
    }
    for (const auto& [na, nb] : f.pairs) {
      const std::uint32_t i = find(na);
      const std::uint32_t j = find(nb);
      d.push_back(distance(scene.model_of(i), objects[i].pose(f.frame), scene.model_of(j),
                           objects[j].pose(f.frame))
                      .distance);
    }
    f.distances = std::move(d);
  }
}

std::string to_json(const RunResult& result) {
  json root;
  root["method"] = result.method;
  root["scene"] = result.scene;
  root["delta"] = result.delta;
  root["seed"] = result.seed;
  root["threads"] = result.threads;
  if (!result.verdict.empty()) {
    root["verdict"] = result.verdict;
    root["memory"] = result.memory;
    root["leaf_scan"] = result.leaf_scan;
  }
  if (result.volume) root["volume"] = true;
  if (result.continuous) root["continuous"] = true;
  root["build_ms"] = result.build_ms;
  root["total_ms"] = result.total_ms;
  json frames = json::array();
  for (const FrameRecord& f : result.frames) {
    json jf;
    jf["frame"] = f.frame;
    jf["pairs"] = pairs_json(f.pairs);
    jf["time_ms"] = f.time_ms;
    jf["candidates"] = pairs_json(f.candidates);
    if (f.feature_hits) jf["feature_hits"] = *f.feature_hits;
    if (f.feature_truth) jf["feature_truth"] = *f.feature_truth;
    if (f.evaluations) {
      jf["evaluations"] = *f.evaluations;
      jf["undecided"] = pairs_json(f.undecided);
    }
    if (f.distances) jf["distances"] = *f.distances;
    if (f.toi) jf["toi"] = *f.toi;
    if (f.contact_points) jf["contact_points"] = *f.contact_points;
    if (!f.self_pairs.empty()) {
      json self = json::array();
      for (const auto& [name, triangles] : f.self_pairs) {
        self.push_back({{"object", name}, {"triangles", triangles}});
      }
      jf["self_pairs"] = std::move(self);
    }
    frames.push_back(std::move(jf));
  }
  root["frames"] = std::move(frames);
  return root.dump(1) + "\n";
}

RunResult parse_run_result(std::string_view text, const std::string& source) {
  check_shape(text, source);  // before the tree is built
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception&) {
    fail(source, "not valid JSON");
  }
  if (!root.is_object()) fail(source, "not a run result (expected a JSON object)");
  RunResult out;
  if (!root.contains("method") || !root["method"].is_string()) fail(source, "missing 'method'");
  out.method = root["method"].get<std::string>();
  if (root.contains("scene") && root["scene"].is_string())
    out.scene = root["scene"].get<std::string>();
  if (root.contains("delta") && root["delta"].is_number()) out.delta = root["delta"].get<double>();
  if (root.contains("seed") && root["seed"].is_number_unsigned())
    out.seed = root["seed"].get<std::uint64_t>();
  if (root.contains("threads") && root["threads"].is_number_integer())
    out.threads = root["threads"].get<int>();
  if (root.contains("verdict") && root["verdict"].is_string())
    out.verdict = root["verdict"].get<std::string>();
  if (root.contains("memory") && root["memory"].is_boolean())
    out.memory = root["memory"].get<bool>();
  if (root.contains("leaf_scan") && root["leaf_scan"].is_boolean()) {
    out.leaf_scan = root["leaf_scan"].get<bool>();
  }
  if (root.contains("volume") && root["volume"].is_boolean())
    out.volume = root["volume"].get<bool>();
  if (root.contains("continuous") && root["continuous"].is_boolean()) {
    out.continuous = root["continuous"].get<bool>();
  }
  out.build_ms = number(root, "build_ms", source, "");
  out.total_ms = number(root, "total_ms", source, "");
  if (!root.contains("frames") || !root["frames"].is_array())
    fail(source, "missing 'frames' array");
  for (const json& jf : root["frames"]) {
    if (!jf.is_object()) fail(source, "each frame must be an object");
    FrameRecord f;
    if (!jf.contains("frame") || !jf["frame"].is_number_unsigned()) {
      fail(source, "a frame has no 'frame' index");
    }
    f.frame = jf["frame"].get<std::size_t>();
    const std::string where = "frame " + std::to_string(f.frame) + ": ";
    if (!jf.contains("pairs")) fail(source, where + "missing 'pairs'");
    f.pairs = parse_pairs(jf["pairs"], source, where + "'pairs'");
    f.time_ms = number(jf, "time_ms", source, where);
    if (jf.contains("candidates"))
      f.candidates = parse_pairs(jf["candidates"], source, where + "'candidates'");
    if (jf.contains("feature_hits") && jf["feature_hits"].is_number_unsigned()) {
      f.feature_hits = jf["feature_hits"].get<std::uint64_t>();
    }
    if (jf.contains("feature_truth") && jf["feature_truth"].is_number_unsigned()) {
      f.feature_truth = jf["feature_truth"].get<std::uint64_t>();
    }
    if (jf.contains("evaluations") && jf["evaluations"].is_number_unsigned()) {
      f.evaluations = jf["evaluations"].get<std::uint64_t>();
    }
    if (jf.contains("undecided"))
      f.undecided = parse_pairs(jf["undecided"], source, where + "'undecided'");
    if (jf.contains("distances")) {
      f.distances =
          per_pair_numbers(jf["distances"], f.pairs.size(), source, where, "distances", false);
    }
    if (jf.contains("toi")) {
      f.toi = per_pair_numbers(jf["toi"], f.pairs.size(), source, where, "toi", true);
    }
    if (jf.contains("contact_points")) {
      const json& c = jf["contact_points"];
      if (!c.is_array() || c.size() != f.pairs.size()) {
        fail(source, where + "'contact_points' must be an array of one point per pair");
      }
      f.contact_points.emplace();
      for (const json& p : c) {
        if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
            !p[2].is_number()) {
          fail(source, where + "'contact_points' must hold points [x, y, z]");
        }
        f.contact_points->push_back({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
      }
    }
    if (jf.contains("self_pairs")) {
      const json& sp = jf["self_pairs"];
      if (!sp.is_array()) fail(source, where + "'self_pairs' must be an array");
      for (const json& e : sp) {
        if (!e.is_object() || !e.contains("object") || !e["object"].is_string() ||
            !e.contains("triangles") || !e["triangles"].is_array()) {
          fail(source, where + "'self_pairs' must hold {\"object\": name, \"triangles\": [...]}");
        }
        std::vector<std::array<std::uint32_t, 2>> triangles;
        for (const json& t : e["triangles"]) {
          if (!t.is_array() || t.size() != 2 || !t[0].is_number_unsigned() ||
              !t[1].is_number_unsigned() || t[0].get<std::uint64_t>() > UINT32_MAX ||
              t[1].get<std::uint64_t>() > UINT32_MAX) {
            fail(source, where + "'self_pairs' triangles must be pairs of triangle indices");
          }
          triangles.push_back({t[0].get<std::uint32_t>(), t[1].get<std::uint32_t>()});
        }
        f.self_pairs.emplace_back(e["object"].get<std::string>(), std::move(triangles));
      }
    }
    out.frames.push_back(std::move(f));
  }
  return out;
}

Metrics compare_runs(const RunResult& truth, const RunResult& result) {
  if (truth.frames.size() != result.frames.size()) {
    throw Error("the runs cover different frames (" + std::to_string(truth.frames.size()) + " vs " +
                std::to_string(result.frames.size()) + ")");
  }
  Metrics m;
  m.frames = truth.frames.size();
  std::uint64_t hits = 0;
  std::uint64_t truth_features = 0;
  bool have_features = false;
  std::vector<double> times, truth_times;
  for (std::size_t k = 0; k < truth.frames.size(); ++k) {
    const FrameRecord& t = truth.frames[k];
    const FrameRecord& r = result.frames[k];
    if (t.frame != r.frame) {
      throw Error("frame " + std::to_string(t.frame) + " of the truth faces frame " +
                  std::to_string(r.frame) + " of the result");
    }
    std::set<NamePair> true_set, reported;
    for (const auto& p : t.pairs) true_set.insert(key(p));
    for (const auto& p : r.pairs) reported.insert(key(p));
    m.true_pairs += true_set.size();
    m.reported_pairs += reported.size();
    for (const auto& p : reported) m.true_positives += true_set.count(p);
    for (const auto& c : t.candidates) {
      ++m.candidate_pairs;
      const NamePair kc = key(c);
      m.correct_candidates += (true_set.count(kc) > 0) == (reported.count(kc) > 0);
    }
    if (r.feature_hits && r.feature_truth) {
      have_features = true;
      hits += *r.feature_hits;
      truth_features += *r.feature_truth;
    }
    times.push_back(r.time_ms);
    truth_times.push_back(t.time_ms);
  }
  const auto ratio = [](std::uint64_t num, std::uint64_t den) {
    return den == 0 ? 1.0 : static_cast<double>(num) / static_cast<double>(den);
  };
  m.recall = ratio(m.true_positives, m.true_pairs);
  m.precision = ratio(m.true_positives, m.reported_pairs);
  m.accuracy = ratio(m.correct_candidates, m.candidate_pairs);
  if (have_features) m.feature_recall = ratio(hits, truth_features);
  m.mean_ms = mean(times);
  m.p99_ms = quantile(times, 0.99);
  m.truth_mean_ms = mean(truth_times);
  m.truth_p99_ms = quantile(truth_times, 0.99);
  return m;
}

}  // namespace antcd::shared
