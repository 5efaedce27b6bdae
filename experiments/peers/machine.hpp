// experiments/peers/machine.hpp — what the report says about the machine and its load (Linux
// /proc and getrusage).
#pragma once

#include <string>

namespace antcd::experiments::peers_bench {

/// The CPU's model name from /proc/cpuinfo ("unknown" when absent).
std::string cpu_model();
/// The 1, 5 and 15 minute load averages from /proc/loadavg.
std::string load_average();
/// Resident set size of this process now, in MiB (from /proc/self/statm).
double rss_mib();
/// Peak resident set size of this process, in MiB.
double peak_rss_mib();
/// "YYYY-MM-DD HH:MM UTC".
std::string today();

}  // namespace antcd::experiments::peers_bench
