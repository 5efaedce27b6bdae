// The report of `antcd bench peers`: Markdown sections and CSV files written from the measured
// runs, and the targets each section checks.
#include "peers/report.hpp"

#include "peers/adapters/bullet.hpp"
#include "peers/adapters/fcl.hpp"
#include "peers/machine.hpp"
#include "shared/statistics.hpp"

#include <antcd/bvh.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <thread>

namespace antcd::experiments::peers_bench {
namespace {

using shared::mean;
using shared::median;

double p99(const std::vector<double>& v) { return shared::quantile(v, 0.99); }

/// Three significant digits; "—" when not finite.
std::string num(double x) {
  if (!std::isfinite(x)) return "—";
  std::ostringstream os;
  const double a = std::abs(x);
  if (a >= 100) {
    os << std::fixed << std::setprecision(0) << x;
  } else if (a >= 10) {
    os << std::fixed << std::setprecision(1) << x;
  } else if (a >= 1) {
    os << std::fixed << std::setprecision(2) << x;
  } else if (a >= 0.1) {
    os << std::fixed << std::setprecision(3) << x;
  } else if (a == 0) {
    os << "0";
  } else {
    os << std::setprecision(3) << x;
  }
  return os.str();
}

/// a / b with two decimals; "—" when b is not positive or a not finite.
std::string ratio(double a, double b) {
  if (!(b > 0) || !std::isfinite(a)) return "—";
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << a / b;
  return os.str();
}

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string verdict(bool ok) { return ok ? "met" : "MISSED"; }

}  // namespace

void write_header(std::ostream& md, const PeersBenchOptions& options, std::size_t frames_wanted) {
  md << "# antcd vs FCL and Bullet (`antcd bench peers`)\n\n";
  md << "- run: " << today() << (options.quick ? ", --quick" : "") << ", --threads "
     << options.threads << ", frames per scene " << frames_wanted << "\n";
  md << "- machine: " << std::thread::hardware_concurrency() << " logical CPUs (nproc "
     << sysconf(_SC_NPROCESSORS_ONLN) << "), CPU \"" << cpu_model() << "\"\n";
  md << "- peers: " << peers::fcl_version() << ", " << peers::bullet_version()
     << "; antcd default BuildOptions (leaf size 4, area-weighted covariance)\n";
  md << "- times: each frame (or pose) runs every engine in turn, so all see the same machine "
        "load. Scenes: CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID) and wall time "
        "(steady_clock) per frame; single-thread ratios and targets use the CPU medians (the "
        "machine is shared, and CPU time is much less disturbed by other work than wall time); "
        "the threaded run can only be judged by wall time. Pairs and builds: wall time per query "
        "or build, medians.\n\n";
}

void write_scenes(std::ostream& md, const std::vector<SceneRun>& scene_runs,
                  std::vector<Target>& targets, PeersBenchResult& result) {
  md << "## Scenes\n\n";
  md << "Per frame: poses → broad phase → narrow phase on every surviving pair. antcd: "
        "`Scene::run_frame` with `Method::Exact` (all contacts: that frame, then "
        "`collide(all_contacts)` on each colliding object pair). FCL: one `BVHModel` per mesh "
        "behind `DynamicAABBTreeCollisionManagerd` (moving objects re-posed and refitted each "
        "frame), `fcl::collide` per overlapping pair, boolean = `num_max_contacts` 1, all "
        "contacts = 10^7 without contact points. Bullet: `btGImpactMeshShape` (margin 0) in a "
        "`btCollisionWorld` with `btDbvtBroadphase`, `performDiscreteCollisionDetection`, a "
        "pair collides when its manifold has a point of distance ≤ 0 (Bullet keeps at most 4 "
        "points per pair, so it gives object pairs only).\n\n";
  for (const SceneRun& run : scene_runs) {
    const Series* base = run.find("antcd exact", "boolean");
    md << "### Scene `" << run.name << "`\n\n"
       << run.description << ". " << run.objects << " objects (" << run.moving << " moving), "
       << run.models << " distinct meshes, " << run.triangles << " triangles in all, " << run.frames
       << " frames; antcd: " << num(base->candidates / static_cast<double>(run.frames))
       << " candidate pairs and " << num(run.colliding / static_cast<double>(run.frames))
       << " colliding object pairs per frame (mean), "
       << num(run.contacts / static_cast<double>(run.frames))
       << " colliding triangle pairs per frame.\n\n";
    md << "| engine | query | broad-phase pairs / frame | median CPU ms | p99 CPU ms | median "
          "wall ms | p99 wall ms | antcd / engine (CPU medians) | antcd / engine (wall "
          "medians) |\n";
    md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const Series& s : run.series) {
      const Series* ref = run.find("antcd exact", s.query);
      if (s.query == "contact manifolds") ref = base;
      const bool threaded = s.engine.find("threads") != std::string::npos;
      const bool self = ref == nullptr || ref == &s;
      md << "| " << s.engine << " | " << s.query << " | "
         << num(s.candidates / static_cast<double>(run.frames)) << " | "
         << (threaded ? "—" : num(median(s.cpu_ms))) << " | "
         << (threaded ? "—" : num(p99(s.cpu_ms))) << " | " << num(median(s.wall_ms)) << " | "
         << num(p99(s.wall_ms)) << " | "
         << (self       ? "1"
             : threaded ? "—"
                        : ratio(median(ref->cpu_ms), median(s.cpu_ms)))
         << " | " << (self ? "1" : ratio(median(ref->wall_ms), median(s.wall_ms))) << " |\n";
    }
    md << "\n";
    if (run.threads > 1) {
      const Series* t =
          run.find("antcd exact, " + std::to_string(run.threads) + " threads", "boolean");
      if (t != nullptr) {
        md << "antcd boolean with " << run.threads
           << " threads (oneTBB): " << ratio(median(base->wall_ms), median(t->wall_ms))
           << "× the speed of 1 thread (wall medians " << num(median(base->wall_ms)) << " → "
           << num(median(t->wall_ms))
           << " ms). CPU time of all threads per frame: " << num(median(base->process_ms))
           << " ms with 1 thread, " << num(median(t->process_ms)) << " ms with " << run.threads
           << " (the work the threads share; wall time can only drop below it / threads when "
              "the cores are free).\n\n";
      }
    }
    std::map<std::string, std::size_t> by_engine;
    for (const Disagreement& d : run.disagreements) ++by_engine[d.other];
    std::vector<std::string> others;
    if (run.threads > 1) others.push_back("antcd " + std::to_string(run.threads) + " threads");
    for (const char* e :
         {"FCL-OBBRSS", "FCL-OBBRSS all-contacts", "FCL-OBB", "FCL-OBB all-contacts", "Bullet"}) {
      others.emplace_back(e);
    }
    md << "Agreement with antcd (1 thread) over " << run.frames
       << " frames, object pairs per frame (all-contacts runs: also the colliding triangle "
          "pairs of each object pair): ";
    for (std::size_t e = 0; e < others.size(); ++e) {
      const std::size_t n = by_engine[others[e]];
      md << (e == 0 ? "" : "; ") << others[e] << " "
         << (n == 0 ? "identical on every frame" : std::to_string(n) + " disagreement(s)");
    }
    md << ".\n\n";
    if (!run.disagreements.empty()) {
      md << "| frame | objects | pair | antcd | other | other says | detail |\n";
      md << "| --- | --- | --- | --- | --- | --- | --- |\n";
      std::size_t shown = 0;
      for (const Disagreement& d : run.disagreements) {
        if (shown++ == 40) {
          md << "| … | | | | | | " << run.disagreements.size() - 40
             << " more in disagreements.csv |\n";
          break;
        }
        md << "| " << d.frame << " | " << d.object_a << ", " << d.object_b << " | " << d.name_a
           << " – " << d.name_b << " | " << (d.reference_says ? "collide" : "apart") << " | "
           << d.other << " | " << (d.other_says ? "collide" : "apart") << " | " << d.detail
           << " |\n";
      }
      md << "\n";
    }
    for (const Disagreement& d : run.disagreements) {
      if (d.other.rfind("FCL", 0) == 0 || d.other.rfind("antcd", 0) == 0) {
        result.antcd_fcl_agree = false;
      } else {
        ++result.bullet_disagreements;
      }
    }
  }
  // Scene targets.
  for (const SceneRun& run : scene_runs) {
    const Series* ab = run.find("antcd exact", "boolean");
    const Series* fb = run.find("FCL-OBBRSS", "boolean");
    const Series* aa = run.find("antcd exact", "all contacts");
    const Series* fa = run.find("FCL-OBBRSS", "all contacts");
    auto measured = [](const Series* x, const Series* y) {
      return "antcd/FCL " + ratio(median(x->cpu_ms), median(y->cpu_ms)) + " CPU (" +
             num(median(x->cpu_ms)) + " vs " + num(median(y->cpu_ms)) + " ms), " +
             ratio(median(x->wall_ms), median(y->wall_ms)) + " wall";
    };
    const double rb = median(ab->cpu_ms) / median(fb->cpu_ms);
    targets.push_back({"scene `" + run.name + "`: exact boolean ≤ 1/3 of FCL-OBBRSS per frame",
                       measured(ab, fb), verdict(rb <= 1.0 / 3.0)});
    const double ra = median(aa->cpu_ms) / median(fa->cpu_ms);
    targets.push_back({"scene `" + run.name + "`: all contacts ≤ 1/2 of FCL-OBBRSS per frame",
                       measured(aa, fa), verdict(ra <= 0.5)});
  }
  for (const SceneRun& run : scene_runs) {
    if (run.name != "dense" && scene_runs.size() > 1) continue;
    const Series* ab = run.find("antcd exact", "boolean");
    const Series* at =
        run.find("antcd exact, " + std::to_string(run.threads) + " threads", "boolean");
    if (at == nullptr) {
      targets.push_back({"scene `" + run.name + "`: 2 threads ≥ 1.6× faster than 1",
                         "not run (--threads 1)", "not measured"});
    } else {
      const double speedup = median(ab->wall_ms) / median(at->wall_ms);
      targets.push_back({"scene `" + run.name + "`: " + std::to_string(run.threads) +
                             " threads ≥ 1.6× faster than 1",
                         ratio(median(ab->wall_ms), median(at->wall_ms)) + "×",
                         verdict(speedup >= 1.6)});
    }
  }
}

void write_pairs(std::ostream& md, const std::vector<PairCell>& cells, std::size_t poses,
                 std::vector<Target>& targets, PeersBenchResult& result) {
  md << "## Mesh pairs: torus tumbling past torus\n\n";
  md << "Both models are the torus `make_torus(1, 0.4, 2k, k)` (4k² triangles; k = 16, 50, 158, "
        "500). A is fixed; for pose i of "
     << poses
     << " B turns by 4π·i/(P−1) about a tilted axis (two full turns) and sits at s·d from A, "
        "the direction d sweeping half a turn around A. s* is the contact distance along d "
        "(scan and bisection with antcd's boolean query, to ~1e-13 relative), R the bounding "
        "radius (1.4). Clearances: "
     << "deep " << clearance_rule(Clearance::Deep) << ", shallow "
     << clearance_rule(Clearance::Shallow) << ", touching " << clearance_rule(Clearance::Touching)
     << ", just separated " << clearance_rule(Clearance::Separated)
     << ". Times: medians over the poses of one query, µs; FCL is `BVHModel<OBBRSSd>`; "
        "boolean = first contact, all = every colliding triangle pair (FCL without contact "
        "points). Every pose compares both verdicts and the sets of colliding triangle "
        "pairs.\n\n";
  md << "| triangles | clearance | colliding poses antcd / FCL | triangle pairs antcd / FCL | "
        "boolean antcd µs | boolean FCL µs | antcd/FCL | all antcd µs | all FCL µs | antcd/FCL "
        "| disagreements |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  double worst_bool = 0;
  double worst_all = 0;
  std::string worst_bool_at;
  std::string worst_all_at;
  for (const PairCell& c : cells) {
    const double rb = median(c.antcd_bool_us) / median(c.fcl_bool_us);
    const double ra = median(c.antcd_all_us) / median(c.fcl_all_us);
    if (rb > worst_bool) {
      worst_bool = rb;
      worst_bool_at = std::to_string(c.triangles) + " " + clearance_name(c.clearance);
    }
    if (ra > worst_all) {
      worst_all = ra;
      worst_all_at = std::to_string(c.triangles) + " " + clearance_name(c.clearance);
    }
    md << "| " << c.triangles << " | " << clearance_name(c.clearance) << " | " << c.colliding_antcd
       << " / " << c.colliding_fcl << " of " << c.poses << " | " << c.triangle_pairs_antcd << " / "
       << c.triangle_pairs_fcl << " | " << num(median(c.antcd_bool_us)) << " | "
       << num(median(c.fcl_bool_us)) << " | "
       << ratio(median(c.antcd_bool_us), median(c.fcl_bool_us)) << " | "
       << num(median(c.antcd_all_us)) << " | " << num(median(c.fcl_all_us)) << " | "
       << ratio(median(c.antcd_all_us), median(c.fcl_all_us)) << " | " << c.disagreements
       << (c.first_disagreement.empty() ? "" : " (" + c.first_disagreement + ")") << " |\n";
    if (c.disagreements > 0) result.antcd_fcl_agree = false;
  }
  md << "\n";
  targets.push_back({"pairs: boolean faster than FCL at every size and clearance",
                     "worst antcd/FCL " + num(worst_bool) + " (" + worst_bool_at + ")",
                     verdict(worst_bool < 1)});
  targets.push_back({"pairs: all contacts faster than FCL at every size and clearance",
                     "worst antcd/FCL " + num(worst_all) + " (" + worst_all_at + ")",
                     verdict(worst_all < 1)});
}

void write_build(std::ostream& md, const std::vector<BuildRow>& builds, bool quick,
                 std::vector<Target>& targets) {
  md << "## Hierarchy build and memory\n\n";
  md << "Build: median wall time of " << (quick ? "3" : "5 (1M: 3)")
     << " constructions (antcd `Model(mesh)`, the mesh copy made before the clock; FCL "
        "`beginModel` / `addSubModel` / `endModel`, default splitter). Memory: antcd "
        "`BvhStats::memory_bytes` (its mesh copy, nodes, leaf triangle indices and packed leaf "
        "vertices); FCL estimated as getNumBVs() × sizeof(BVNode<BV>) ("
     << sizeof(fcl::BVNode<fcl::OBBRSSd>) << " B for OBBRSS, " << sizeof(fcl::BVNode<fcl::OBBd>)
     << " B for OBB) + vertices × 24 B + triangles × 24 B (its primitive index array, 4 B per "
        "triangle, is not counted). antcd nodes are "
     << sizeof(BvhNode) << " B.\n\n";
  md << "| triangles | antcd build ms | FCL-OBBRSS ms | antcd/FCL | FCL-OBB ms | antcd nodes | "
        "FCL BVs | antcd B/triangle | FCL-OBBRSS B/triangle | antcd/FCL | FCL-OBB B/triangle "
        "|\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  double worst_build = 0;
  double worst_mem = 0;
  for (const BuildRow& b : builds) {
    worst_build = std::max(worst_build, b.antcd_ms / b.fcl_obbrss_ms);
    worst_mem = std::max(worst_mem, b.antcd_bytes_per_tri / b.fcl_obbrss_bytes_per_tri);
    md << "| " << b.triangles << " | " << num(b.antcd_ms) << " | " << num(b.fcl_obbrss_ms) << " | "
       << ratio(b.antcd_ms, b.fcl_obbrss_ms) << " | " << num(b.fcl_obb_ms) << " | " << b.antcd_nodes
       << " | " << b.fcl_bvs << " | " << num(b.antcd_bytes_per_tri) << " | "
       << num(b.fcl_obbrss_bytes_per_tri) << " | "
       << ratio(b.antcd_bytes_per_tri, b.fcl_obbrss_bytes_per_tri) << " | "
       << num(b.fcl_obb_bytes_per_tri) << " |\n";
  }
  md << "\n";
  targets.push_back({"build ≤ 1/2 of FCL-OBBRSS's time at every size",
                     "worst antcd/FCL " + num(worst_build), verdict(worst_build <= 0.5)});
  targets.push_back({"memory per triangle ≤ FCL-OBBRSS's at every size",
                     "worst antcd/FCL " + num(worst_mem), verdict(worst_mem <= 1)});
}

void write_pair_csvs(const std::vector<PairCell>& cells, const std::vector<BuildRow>& builds,
                     PeersBenchResult& result) {
  std::ostringstream pc;
  pc << "triangles,clearance,poses,colliding_antcd,colliding_fcl,triangle_pairs_antcd,"
        "triangle_pairs_fcl,bool_antcd_us,bool_fcl_us,all_antcd_us,all_fcl_us,disagreements\n";
  for (const PairCell& c : cells) {
    pc << c.triangles << ',' << clearance_name(c.clearance) << ',' << c.poses << ','
       << c.colliding_antcd << ',' << c.colliding_fcl << ',' << c.triangle_pairs_antcd << ','
       << c.triangle_pairs_fcl << ',' << median(c.antcd_bool_us) << ',' << median(c.fcl_bool_us)
       << ',' << median(c.antcd_all_us) << ',' << median(c.fcl_all_us) << ',' << c.disagreements
       << '\n';
  }
  result.csv.emplace_back("pairs.csv", pc.str());
  std::ostringstream bc;
  bc << "triangles,antcd_build_ms,fcl_obbrss_build_ms,fcl_obb_build_ms,antcd_bytes_per_tri,"
        "fcl_obbrss_bytes_per_tri,fcl_obb_bytes_per_tri\n";
  for (const BuildRow& b : builds) {
    bc << b.triangles << ',' << b.antcd_ms << ',' << b.fcl_obbrss_ms << ',' << b.fcl_obb_ms << ','
       << b.antcd_bytes_per_tri << ',' << b.fcl_obbrss_bytes_per_tri << ','
       << b.fcl_obb_bytes_per_tri << '\n';
  }
  result.csv.emplace_back("build.csv", bc.str());
}

void write_scale(std::ostream& md, const std::vector<ScaleRow>& rows, std::size_t frames,
                 PeersBenchResult& result) {
  md << "## Scale: objects vs candidate pairs vs time per frame (antcd exact, 1 thread)\n\n";
  md << "The production-line generator with `--objects N --vertices V` (V lowered with N to "
        "keep about 2 million triangles in all at 1 000 and more objects), "
     << frames
     << " frames each, boolean exact. Resident memory is the whole process's after the run "
        "(it includes what earlier sections left allocated).\n\n";
  md << "| objects | --vertices | triangles in all | distinct meshes | hierarchy MiB | build ms "
        "| "
        "candidate pairs / frame | colliding pairs / frame | median ms / frame | p99 ms | µs "
        "per candidate pair | RSS MiB |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::ostringstream sc;
  sc << "objects,vertices_option,triangles,models,frames,candidates_per_frame,colliding_per_"
        "frame,median_ms,p99_ms,build_ms,model_mib,rss_mib\n";
  for (const ScaleRow& r : rows) {
    md << "| " << r.objects << " | " << r.vertices_option << " | " << r.triangles << " | "
       << r.models << " | " << num(r.model_mib) << " | " << num(r.build_ms) << " | "
       << num(r.candidates) << " | " << num(r.colliding) << " | " << num(r.median_ms) << " | "
       << num(r.p99_ms) << " | " << (r.candidates > 0 ? num(1e3 * r.median_ms / r.candidates) : "—")
       << " | " << num(r.rss_mib) << " |\n";
    sc << r.objects << ',' << r.vertices_option << ',' << r.triangles << ',' << r.models << ','
       << r.frames << ',' << r.candidates << ',' << r.colliding << ',' << r.median_ms << ','
       << r.p99_ms << ',' << r.build_ms << ',' << r.model_mib << ',' << r.rss_mib << '\n';
  }
  md << "\nPeak resident memory of the process: " << num(peak_rss_mib()) << " MiB.\n\n";
  result.csv.emplace_back("scale.csv", sc.str());
}

void write_footer(std::ostream& md, const std::vector<Target>& targets,
                  const PeersBenchResult& result, double total_s, const std::string& load_start) {
  if (!targets.empty()) {
    md << "## Targets (single thread unless stated)\n\n| target | measured | verdict |\n"
          "| --- | --- | --- |\n";
    for (const Target& t : targets) {
      md << "| " << t.what << " | " << t.measured << " | " << t.verdict << " |\n";
    }
    md << "\n";
  }
  md << "Agreement: "
     << (result.antcd_fcl_agree ? "antcd and FCL agreed on every frame and pose."
                                : "antcd and FCL DISAGREED (see above).")
     << " Bullet disagreements with antcd: " << result.bullet_disagreements << ".\n\n";
  md << "Run time " << num(total_s) << " s; load average " << load_start << " at the start, "
     << load_average() << " at the end.\n";
}

void write_scene_csvs(const std::vector<SceneRun>& scene_runs, PeersBenchResult& result) {
  std::ostringstream sc;
  sc << "scene,engine,query,frames,candidates_per_frame,median_ms,p99_ms,mean_ms,median_cpu_"
        "ms\n";
  for (const SceneRun& run : scene_runs) {
    for (const Series& s : run.series) {
      sc << run.name << ',' << csv_escape(s.engine) << ',' << csv_escape(s.query) << ','
         << run.frames << ',' << s.candidates / static_cast<double>(run.frames) << ','
         << median(s.wall_ms) << ',' << p99(s.wall_ms) << ',' << mean(s.wall_ms) << ','
         << median(s.cpu_ms) << '\n';
    }
  }
  result.csv.emplace_back("scenes.csv", sc.str());
  std::ostringstream dc;
  dc << "scene,frame,object_a,object_b,name_a,name_b,antcd,engine,engine_says,detail\n";
  for (std::size_t s = 0; s < scene_runs.size(); ++s) {
    for (const Disagreement& d : scene_runs[s].disagreements) {
      dc << d.scene << ',' << d.frame << ',' << d.object_a << ',' << d.object_b << ','
         << csv_escape(d.name_a) << ',' << csv_escape(d.name_b) << ','
         << (d.reference_says ? "collide" : "apart") << ',' << csv_escape(d.other) << ','
         << (d.other_says ? "collide" : "apart") << ',' << csv_escape(d.detail) << '\n';
    }
  }
  result.csv.emplace_back("disagreements.csv", dc.str());
}

}  // namespace antcd::experiments::peers_bench
