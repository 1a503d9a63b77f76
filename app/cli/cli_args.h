// Tiny argument parser for the subcommands: positional arguments plus --flag and --key value options.
// Unknown options are errors, so a typo never silently changes a batch job.
#pragma once

#include <cstdint>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace ug::cli {

struct Args {
    std::vector<std::string> positional;
    std::map<std::string, std::string> options;  // "--threads" -> "2"; flags map to ""

    bool has(const std::string& key) const { return options.count(key) != 0; }
    std::string get(const std::string& key, const std::string& fallback = "") const {
        auto it = options.find(key);
        return it == options.end() ? fallback : it->second;
    }
};

// `with_value`: options that take a value; `flags`: options that don't.
bool parseArgs(int argc, char** argv, int first, const std::set<std::string>& with_value,
               const std::set<std::string>& flags, Args* out, std::string* error);

// Parses a whole integer in [lo, hi]; the error names the option.
bool parseInt(const std::string& option, const std::string& text, long lo, long hi, long* out, std::string* error);

// "4G", "512M", "64K" or a plain byte count, in [lo, hi] bytes; the error names the option.
bool parseByteSize(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi, uint64_t* out,
                   std::string* error);

// "1280x720": two whole numbers in [lo, hi]; the error names the option and the accepted range.
bool parseSize(const std::string& option, const std::string& text, long lo, long hi, int* width, int* height,
               std::string* error);

// "a,b,c,...": comma-separated finite numbers (each consumed whole); the error names the option and the
// item. The count is the caller's to check.
bool parseNumberList(const std::string& option, const std::string& text, std::vector<double>* out, std::string* error);

// The assets folder: $UG_ASSETS, else <exe>/../assets or <exe>/../../assets, else the source tree's.
std::string assetsDir();

// This executable's absolute path (/proc/self/exe), or "undergrowth" when it cannot be read: what
// region-job scripts and the bench run.
std::string selfExecutablePath();

// A word for the shell: single-quoted, inner quotes escaped.
std::string shellQuote(const std::string& s);

}  // namespace ug::cli
