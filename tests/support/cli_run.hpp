// Runs a built program (the antcd tool) for the CLI tests: output captured, a time limit.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace antcd::test {

struct CliRun {
  int exit_code = -1;  ///< the exit status, or -1 when killed by a signal
  int signal = 0;
  bool timed_out = false;
  std::string out;
  std::string err;
};

/// Runs `program args...` in `cwd` (stdin from /dev/null), killing it after `timeout_s`. Its
/// stdout and stderr go through files in the folder `<cwd>_io` beside `cwd`.
CliRun run_program(const std::string& program, const std::vector<std::string>& args,
                   const std::filesystem::path& cwd, double timeout_s = 120);

/// The CLI's refusal contract (issue 28), as GoogleTest expectations: no hang, no signal, exit
/// code 2, nothing on stdout, and exactly one stderr line "error: ..." that is printable (no
/// control byte), bounded (antcd::kPrintableLineLength) and holds `named`.
void expect_clean_refusal(const CliRun& r, const std::string& named);

}  // namespace antcd::test
