// antcd — command-line front end of the antcd collision library.
#include "cli_util.hpp"
#include "lab.hpp"

#include <antcd/error.hpp>
#include <antcd/file.hpp>
#include <antcd/version.hpp>

#include <cstdio>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace {

int fail(const std::string& message) {
  // Printable and bounded: the message may quote file content or names (antcd/file.hpp).
  std::cerr << "error: " << antcd::printable_line(message) << '\n';
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
#if !defined(ANTCD_LAB)
  // learn, bench, run --method box-*: antcd-lab's (lab.hpp).
  if (antcd::cli::runs_in_lab(argc, argv)) return antcd::cli::exec_lab(argc, argv);
#endif
  CLI::App app{
      "antcd: collision detection between triangle meshes (hybrid Sphere-OBB hierarchy, "
      "exact triangle tests, ant-colony random detection)",
      "antcd"};
  app.require_subcommand(1);
  const std::string version = std::string("antcd ") + antcd::kVersion;
  app.set_version_flag("--version", version);
  int code = 0;
  antcd::cli::add_collide_command(app, code);
  antcd::cli::add_distance_command(app, code);
  antcd::cli::add_depth_command(app, code);
  antcd::cli::add_points_command(app, code);
  antcd::cli::add_info_command(app, code);
  antcd::cli::add_demo_command(app, code);
  antcd::cli::add_scene_commands(app, code);
  antcd::cli::add_view_command(app, code);
  antcd::cli::add_ccd_commands(app, code);
  antcd::cli::add_self_commands(app, code);
  antcd::cli::add_deform_ccd_command(app, code);
#if defined(ANTCD_LAB)
  antcd::cli::add_bench_commands(app, code);
  antcd::cli::add_learn_commands(app, code);
#else
  antcd::cli::add_lab_commands(app);
#endif
  // CLI11 would only say "A subcommand is required" for a mistyped command (`antcd frobnicate`,
  // `antcd scene frobnicate`): name it, at every level of subcommands.
  CLI::App* level = &app;
  std::string path;
  for (int i = 1; i < argc && argv[i][0] != '-'; ++i) {
    const auto subs = level->get_subcommands([](CLI::App*) { return true; });
    if (subs.empty()) break;  // the command's own arguments from here
    CLI::App* next = nullptr;
    std::string known;
    for (CLI::App* sub : subs) {
      if (sub->check_name(argv[i])) next = sub;
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (next == nullptr) {
      return fail("unknown command '" + path + argv[i] + "' (expected one of " + known + ")");
    }
    path += next->get_name() + " ";
    level = next;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::cout << version << '\n';
    return 0;
  } catch (const CLI::ParseError& e) {
    // CLI11 checks what is required (a subcommand, positionals) and converts values before it
    // reports the arguments it could not place, so `antcd --bogus` said only "A subcommand is
    // required": name the first such argument, at whatever level it was met.
    const std::vector<std::string> unplaced = app.remaining(true);
    if (!unplaced.empty()) {
      const std::string& arg = unplaced.front();
      const std::string command = "antcd " + path;  // path: the commands before the first option
      std::string line =
          std::string(arg.starts_with('-') ? "unknown option '" : "unexpected argument '") + arg +
          "'";
      if (!path.empty()) line += " for '" + command.substr(0, command.size() - 1) + "'";
      return fail(line + " (see '" + command + "--help')");
    }
    return fail(e.what());
  } catch (const antcd::cli::UsageError& e) {
    return fail(e.what());
  } catch (const antcd::Error& e) {  // antcd/error.hpp: every bad input the library reports
    return fail(e.what());
  } catch (const std::bad_alloc&) {
    return fail("out of memory");
  }
  return code;
}
