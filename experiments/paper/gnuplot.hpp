// experiments/paper/gnuplot.hpp — draws the PNGs by running gnuplot (Debian gnuplot-nox) as a
// child process, each plot from a script written beside it.
#pragma once

#include <filesystem>
#include <string>

namespace antcd::experiments::paper {

class Gnuplot {
 public:
  /// `program`: a name looked up on PATH, or a path. `out`: the folder of the scripts and PNGs.
  Gnuplot(std::string program, std::filesystem::path out);

  /// Fails early (before minutes of measurements) when gnuplot or its PNG terminal is missing:
  /// throws antcd::Error naming gnuplot and the Debian package.
  void check() const;

  /// Writes NAME.gp and draws NAME.png from it: into a temporary file in `out`, then renamed.
  /// Throws antcd::Error with gnuplot's output when it fails.
  void plot(const std::string& name, const std::string& body) const;

 private:
  std::string program_;
  std::filesystem::path out_;
};

}  // namespace antcd::experiments::paper
