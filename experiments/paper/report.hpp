// experiments/paper/report.hpp — report.md of `antcd bench paper`: findings computed from the
// measured data, filled into the Markdown template report_template.md (embedded at build time).
#pragma once

#include "paper/results.hpp"

#include <string>

namespace antcd::experiments::paper {

/// The report: our figures beside the paper's, the choices made where the paper is vague, and
/// where and why the results differ.
std::string write_report(const Results& r);

}  // namespace antcd::experiments::paper
