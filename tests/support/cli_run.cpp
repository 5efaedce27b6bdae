// Runs a built program for the CLI tests (see cli_run.hpp).
#include "support/cli_run.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <antcd/file.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "support/test_support.hpp"

namespace antcd::test {

namespace fs = std::filesystem;

void expect_clean_refusal(const CliRun& r, const std::string& named) {
  EXPECT_FALSE(r.timed_out) << "hung";
  EXPECT_EQ(r.signal, 0) << "killed by signal " << r.signal << "; stderr: " << r.err;
  EXPECT_EQ(r.exit_code, 2) << "stderr: " << r.err;
  EXPECT_EQ(r.err.rfind("error: ", 0), 0U) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << "stderr: " << r.err;
  // Printable (no escape sequence, bell or binary reaches the terminal) and bounded.
  EXPECT_TRUE(std::all_of(r.err.begin(), r.err.end() - (r.err.empty() ? 0 : 1),
                          [](char c) {
                            const auto u = static_cast<unsigned char>(c);
                            return u >= 0x20 && u != 0x7F;
                          }))
      << "stderr: " << printable_line(r.err);
  EXPECT_LE(r.err.size(), kPrintableLineLength + 64) << "stderr: " << r.err.substr(0, 200);
  EXPECT_NE(r.err.find(named), std::string::npos)
      << "stderr does not name " << named << ": " << r.err;
  EXPECT_EQ(r.out, "") << "stdout: " << r.out;
}

CliRun run_program(const std::string& program, const std::vector<std::string>& args,
                   const fs::path& cwd, double timeout_s) {
  const fs::path io = cwd.parent_path() / (cwd.filename().string() + "_io");
  fs::create_directories(io);
  const std::string out_path = (io / "stdout").string();
  const std::string err_path = (io / "stderr").string();
  std::vector<std::string> argv_store = {program};
  argv_store.insert(argv_store.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_store) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir = cwd.string();

  const pid_t pid = ::fork();
  if (pid == 0) {
    // Child: only async-signal-safe calls until exec.
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0 || ::chdir(dir.c_str()) != 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  CliRun r;
  if (pid < 0) {
    ADD_FAILURE() << "fork failed: " << std::strerror(errno);
    return r;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = read_all(out_path);
  r.err = read_all(err_path);
  return r;
}

}  // namespace antcd::test
