// antcd bench peers: antcd against FCL and Bullet on the same scenes and mesh pairs
// (experiments/peers/peers_bench.hpp). Built with the peers only when FCL and Bullet were found
// (ANTCD_HAVE_PEERS); otherwise the command exists and says what is missing.
#include <antcd/file.hpp>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_util.hpp"

#ifdef ANTCD_HAVE_PEERS
#include "peers/peers_bench.hpp"
#endif

namespace antcd::cli {

namespace {

struct PeersArgs {
  std::string scene;
  std::size_t frames = 0;
  int threads = 2;
  bool quick = false;
  std::string out;
  std::vector<std::string> only;
};

}  // namespace

void add_bench_peers_command(CLI::App& bench, int& code) {
  auto args = std::make_shared<PeersArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "peers",
      "antcd against FCL 0.7 and Bullet 3.24, side by side: scenes frame by frame (the generated "
      "paper production line and a dense variant, or SCENE.json), a tumbling mesh pair at four "
      "clearances, build time and memory, and a scale curve. Checks that all agree on every "
      "frame's colliding pairs; prints a Markdown report. Exit code 1 when antcd and FCL "
      "disagree anywhere");
  cmd->add_option("scene", args->scene,
                  "Scene file to run instead of the generated paper scene and its dense variant")
      ->type_name("SCENE.json");
  cmd->add_option("--frames", args->frames, "Frames per scene (default 300, --quick 30)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10'000'000}));
  cmd->add_option("--threads", args->threads,
                  "Threads of antcd's second scene run (oneTBB); 1 = no threaded run")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_flag("--quick", args->quick,
                "Fewer frames, poses and sizes (finishes in well under a minute)");
  cmd->add_option("--out", args->out,
                  "Also write report.md and CSV files (scenes, pairs, build, scale, "
                  "disagreements) into this folder")
      ->check(writable_folder())
      ->type_name("DIR");
  cmd->add_option("--only", args->only, "Run only these sections (repeatable)")
      ->check(CLI::IsMember({"scenes", "pairs", "scale"}))
      ->type_name("scenes|pairs|scale");
  cmd->callback([args, &code] {
#ifdef ANTCD_HAVE_PEERS
    experiments::PeersBenchOptions opts;
    opts.scene_file = args->scene;
    opts.frames = args->frames;
    opts.threads = args->threads;
    opts.quick = args->quick;
    if (!args->only.empty()) {
      auto has = [&](const char* s) {
        for (const std::string& o : args->only) {
          if (o == s) return true;
        }
        return false;
      };
      opts.run_scenes = has("scenes");
      opts.run_pairs = has("pairs");
      opts.run_scale = has("scale");
    }
    const experiments::PeersBenchResult r = experiments::run_peers_bench(opts, std::cerr);
    std::cout << r.report_markdown;
    if (!args->out.empty()) {
      const std::filesystem::path dir(args->out);
      create_folders(dir);
      write_file_atomic(dir / "report.md", r.report_markdown);
      for (const auto& [name, text] : r.csv) write_file_atomic(dir / name, text);
      std::cerr << "wrote " << (dir / "report.md").string() << '\n';
    }
    code = r.antcd_fcl_agree ? 0 : 1;
#else
    (void)args;
    (void)code;
    throw UsageError("antcd was built without FCL/Bullet (install libfcl-dev libbullet-dev)");
#endif
  });
}

}  // namespace antcd::cli
