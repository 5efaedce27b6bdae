#include "paper/gnuplot.hpp"

#include <antcd/file.hpp>
#include <antcd/mesh.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>
#include <vector>

extern char** environ;

namespace antcd::experiments::paper {
namespace {

namespace fs = std::filesystem;

/// Runs gnuplot with `args`, its output into `log_file`. Returns the exit status; throws
/// antcd::Error naming gnuplot when the program cannot be started.
int run_program(const std::string& program, const std::vector<std::string>& args,
                const fs::path& log_file) {
  std::vector<std::string> storage;
  storage.reserve(args.size() + 1);
  storage.push_back(program);
  for (const std::string& a : args) storage.push_back(a);
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const bool has_slash = program.find('/') != std::string::npos;
  const int rc = has_slash
                     ? posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ)
                     : posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    std::error_code ignored;
    fs::remove(log_file, ignored);
    throw Error("cannot run gnuplot ('" + program + "'): " + std::strerror(rc) +
                ". The PNG plots of `antcd bench paper` need gnuplot: install the Debian package "
                "gnuplot-nox (scripts/install-deps.sh, see the README)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("gnuplot ('" + program + "'): waitpid failed");
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::string read_log(const fs::path& log_file) {
  std::string text;
  try {
    text = read_file(log_file);
  } catch (const Error&) {
  }
  std::error_code ignored;
  fs::remove(log_file, ignored);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.size() > 600) text = text.substr(text.size() - 600);
  return text;
}

const char* kTerminal = "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'";

/// gnuplot single-quoted string literal.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

}  // namespace

Gnuplot::Gnuplot(std::string program, fs::path out)
    : program_(std::move(program)), out_(std::move(out)) {}

void Gnuplot::check() const {
  const fs::path log_file = out_ / ".gnuplot-check.log";
  const int status = run_program(program_, {"-e", std::string(kTerminal) + "; exit"}, log_file);
  const std::string log = read_log(log_file);
  if (status != 0) {
    throw Error("gnuplot ('" + program_ + "') cannot draw PNGs (exit status " +
                std::to_string(status) + "): " + log +
                ". Install the Debian package gnuplot-nox (see the README)");
  }
}

void Gnuplot::plot(const std::string& name, const std::string& body) const {
  const fs::path script = out_ / (name + ".gp");
  const fs::path png = out_ / (name + ".png");
  const fs::path tmp = out_ / ("." + name + ".png.tmp");
  const fs::path log_file = out_ / ("." + name + ".gnuplot.log");
  const std::string header =
      "# " + name + ".png, drawn by `antcd bench paper`. Redraw with:\n#   gnuplot -e \"" +
      std::string(kTerminal) + "; set output '" + name + ".png'\" " + name + ".gp\n";
  write_file_atomic(script, header + body);
  std::error_code ignored;
  fs::remove(tmp, ignored);
  const int status = run_program(
      program_,
      {"-e", std::string(kTerminal) + "; set output " + quoted(tmp.string()), script.string()},
      log_file);
  const std::string log = read_log(log_file);
  std::error_code size_error;
  const bool written = fs::exists(tmp) && fs::file_size(tmp, size_error) > 0;
  if (status != 0 || !written) {
    fs::remove(tmp, ignored);
    throw Error("gnuplot ('" + program_ + "') failed to draw " + png.string() + " (exit status " +
                std::to_string(status) + "): " + log);
  }
  fs::rename(tmp, png);
}

}  // namespace antcd::experiments::paper
