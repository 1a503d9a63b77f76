// Benchmark rows, printed as a table and written as JSON:
//   {"results": [{"name", "value", "unit", "target", "paper"}, ...], "machine": {...}}
// "target" is our goal as text ("<= 2"), "paper" the figure the papers report for the same work (or
// null); both let a reader judge a row without opening docs/architecture.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace ug {

struct BenchRow {
    std::string name;   // dotted, stable: "ghosttile.dense.seconds"
    double value = 0.0;
    std::string unit;   // "s", "ms", "pairs", "bytes/pair", ...
    std::string target;  // empty = no target; else e.g. "<= 2"
    std::optional<double> paper;  // the paper's figure for the same row, if any
    std::string note;   // short context: "median of 5", "1.12k / 990k in the paper"
};

// True when the row has a target of the form "<= x" or ">= x" and the value meets it; rows without a
// target count as met.
bool benchTargetMet(const BenchRow& row);

std::string formatBenchTable(const std::vector<BenchRow>& rows);

// Atomic write; errors name the path.
bool writeBenchJson(const std::string& path, const std::vector<BenchRow>& rows, std::string* error);

// Median of a non-empty list (the mean of the middle two for an even count).
double median(std::vector<double> values);

}  // namespace ug
