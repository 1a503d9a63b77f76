#include "io/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace ug {

bool benchTargetMet(const BenchRow& row) {
    if (row.target.size() < 3) return true;
    const std::string op = row.target.substr(0, 2);
    const double bound = std::atof(row.target.c_str() + 2);
    if (op == "<=") return row.value <= bound;
    if (op == ">=") return row.value >= bound;
    return true;
}

namespace {
std::string formatValue(double v) {
    char buf[64];
    if (v != 0.0 && (std::abs(v) >= 1e7 || std::abs(v) < 1e-3)) std::snprintf(buf, sizeof(buf), "%.4g", v);
    else if (v == std::floor(v) && std::abs(v) < 1e15) std::snprintf(buf, sizeof(buf), "%.0f", v);
    else std::snprintf(buf, sizeof(buf), "%.4g", v);
    return buf;
}
}  // namespace

std::string formatBenchTable(const std::vector<BenchRow>& rows) {
    size_t name_w = 4, value_w = 5, unit_w = 4, target_w = 6, paper_w = 5;
    for (const BenchRow& r : rows) {
        name_w = std::max(name_w, r.name.size());
        value_w = std::max(value_w, formatValue(r.value).size());
        unit_w = std::max(unit_w, r.unit.size());
        target_w = std::max(target_w, r.target.size());
        if (r.paper) paper_w = std::max(paper_w, formatValue(*r.paper).size());
    }
    std::string out;
    char line[512];
    std::snprintf(line, sizeof(line), "%-*s  %*s  %-*s  %-*s  %*s  %s\n", int(name_w), "name", int(value_w), "value",
                  int(unit_w), "unit", int(target_w), "target", int(paper_w), "paper", "note");
    out += line;
    out += std::string(name_w + value_w + unit_w + target_w + paper_w + 16, '-') + "\n";
    for (const BenchRow& r : rows) {
        std::string target = r.target.empty() ? "" : r.target + (benchTargetMet(r) ? " ok" : " MISS");
        std::snprintf(line, sizeof(line), "%-*s  %*s  %-*s  %-*s  %*s  %s\n", int(name_w), r.name.c_str(),
                      int(value_w), formatValue(r.value).c_str(), int(unit_w), r.unit.c_str(), int(target_w + 5),
                      target.c_str(), int(paper_w), r.paper ? formatValue(*r.paper).c_str() : "-", r.note.c_str());
        out += line;
    }
    return out;
}

bool writeBenchJson(const std::string& path, const std::vector<BenchRow>& rows, std::string* error) {
    nlohmann::json results = nlohmann::json::array();
    for (const BenchRow& r : rows) {
        nlohmann::json j;
        j["name"] = r.name;
        j["value"] = r.value;
        j["unit"] = r.unit;
        j["target"] = r.target.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.target);
        j["paper"] = r.paper ? nlohmann::json(*r.paper) : nlohmann::json(nullptr);
        if (!r.note.empty()) j["note"] = r.note;
        j["met"] = benchTargetMet(r);
        results.push_back(j);
    }
    nlohmann::json doc;
    doc["results"] = results;
    doc["machine"] = {{"hardware_threads", std::thread::hardware_concurrency()}};
    return writeTextFileAtomically(path, doc.dump(2) + "\n", error);
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    if (n == 0) return 0.0;
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace ug
