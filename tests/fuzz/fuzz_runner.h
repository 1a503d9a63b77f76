// Runs one target's inputs in forked children under a watchdog and records what went wrong
// (fuzz_inputs.cpp's top comment is the manual).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fuzz.h"

namespace ug::fuzz {

struct RunOptions {
    uint64_t runs = 1000;        // inputs, at most
    double seconds = 60.0;       // wall time, at most (whichever comes first)
    uint64_t seed = 1;
    std::string out;             // failing inputs are saved under out/<target>/ ("" = not saved)
    bool keep_going = false;     // record a failure and go on with the next input
    double timeout_s = 10.0;     // one input running longer is a hang
    uint64_t rss_mb = 3000;      // a child resident above this is over memory
    uint64_t batch = 500;        // inputs per forked child
    bool leak_check = true;      // LeakSanitizer after every input (sanitized builds only)
    int save_per_finding = 2;    // inputs saved for each distinct finding
    std::vector<std::string> replay;  // files to run instead of generated inputs
    bool in_process = false;     // replay without forking (for a debugger)
    std::string work_dir;        // scratch folder to use instead of a fresh one (set by the harness itself)
    std::string self_path;       // argv[0], for the reproduce hint
};

struct TargetResult {
    uint64_t inputs = 0;
    uint64_t accepted = 0;
    uint64_t rejected = 0;  // with a message that names the file: the expected result
    uint64_t crashes = 0, hangs = 0, sanitizer = 0, memory = 0, messages = 0, promises = 0;
    uint64_t findings = 0;  // distinct
    double seconds = 0.0;
    double slowest_s = 0.0;
    uint64_t slowest_index = 0;
    bool passed() const { return crashes + hangs + sanitizer + memory + messages + promises == 0 && inputs > 0; }
};

TargetResult fuzzTarget(const Target& target, const Corpus& corpus, const RunOptions& options);

// Shrinks a failing file by deleting ranges while the same finding still happens (options: seconds,
// timeout, rss_mb); writes the result to out_path. Returns non-zero when the file does not fail.
int minimize(const Target& target, const Corpus& corpus, const std::string& file, const RunOptions& options,
             const std::string& out_path);

}  // namespace ug::fuzz
