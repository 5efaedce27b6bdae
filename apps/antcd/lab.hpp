// The split between the two executables. `antcd` (the main tool) links antcd's libraries only, so
// that it starts in milliseconds; `antcd-lab` holds every command of `antcd` plus those that link
// libtorch (the learned baselines), FCL and Bullet (the peers) and the paper's experiments:
//   antcd learn ...                      antcd bench paper | peers ...
//   antcd run ... --method box-dnn | box-lstm ...
// The main tool hands those command lines to antcd-lab unchanged (exec, same arguments), so they
// work as before wherever both are installed (side by side: bin/, or the build's apps/antcd/).
#pragma once

#include <CLI/CLI.hpp>

namespace antcd::cli {

/// True when the command line is one of antcd-lab's commands above.
bool runs_in_lab(int argc, char** argv);

/// Replaces this process by antcd-lab with the same arguments: the antcd-lab beside this
/// executable, else the one on PATH. Returns only on failure, after printing one "error: ..." line:
/// the exit code (2).
int exec_lab(int argc, char** argv);

/// Registers `learn` and `bench` on the main tool, for its --help (runs_in_lab catches them first).
void add_lab_commands(CLI::App& app);

}  // namespace antcd::cli
