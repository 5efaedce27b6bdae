// shared/statistics.hpp — the summary statistics the tools report (run metrics, benchmark
// tables). One definition each; every function answers NaN for an empty list: no data is
// not zero, and NaN shows up as a missing value ("" in CSV, "—" or "n/a" in tables) rather than
// as a plausible number.
#pragma once

#include <vector>

namespace antcd::shared {

/// Arithmetic mean; NaN when `values` is empty.
double mean(const std::vector<double>& values);

/// Median: the middle value, or the mean of the two middle values for an even count (+inf sorts
/// last, so a median over runs that never finished can be +inf). NaN when `values` is empty.
double median(std::vector<double> values);

/// The value at quantile q in [0, 1] by nearest rank: the smallest value with at least q of the
/// list at or below it (q = 0 gives the minimum, q = 1 the maximum). NaN when `values` is empty.
double quantile(std::vector<double> values, double q);

}  // namespace antcd::shared
