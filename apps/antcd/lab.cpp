// The main tool's hand-over to antcd-lab (lab.hpp).
#include "lab.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace antcd::cli {

namespace {

constexpr const char* kLab = "antcd-lab";

bool is_learned_value(std::string_view arg) {
  for (const std::string_view method : {"box-dnn", "box-lstm"}) {
    if (arg == method || (arg.size() > method.size() && arg.ends_with(method) &&
                          arg[arg.size() - method.size() - 1] == '=')) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool runs_in_lab(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command = argv[1];
  if (command == "learn" || command == "bench") return true;
  if (command != "run") return false;
  // A value box-dnn / box-lstm anywhere (--method box-dnn, --method=box-dnn, -m box-dnn): a file
  // of that name would be sent too, which is harmless (antcd-lab runs every command).
  for (int i = 2; i < argc; ++i) {
    if (is_learned_value(argv[i])) return true;
  }
  return false;
}

int exec_lab(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  std::string beside;
  if (!error) {
    beside = (self.parent_path() / kLab).string();
    if (::access(beside.c_str(), X_OK) == 0) {
      args[0] = beside.data();
      ::execv(beside.c_str(), args.data());
    }
  }
  std::string name = kLab;
  args[0] = name.data();
  ::execvp(kLab, args.data());
  const int why = errno;
  std::cerr
      << "error: `antcd " << argv[1] << "` runs in " << kLab
      << " (the learned baselines, the paper's experiments and the peers), which was not found "
      << (beside.empty() ? std::string() : "at " + beside + " nor ") << "on PATH ("
      << std::strerror(why) << ")\n";
  return 2;
}

void add_lab_commands(CLI::App& app) {
  for (const auto& [name, what] :
       {std::pair{"learn", "Train the learned baselines box-dnn / box-lstm (runs antcd-lab)"},
        std::pair{"bench", "Benchmark suites: paper, peers (runs antcd-lab)"}}) {
    CLI::App* cmd = app.add_subcommand(name, what);
    cmd->allow_extras();
    cmd->prefix_command();
  }
}

}  // namespace antcd::cli
