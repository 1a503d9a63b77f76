#include "cli/cli_args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <unistd.h>

namespace ug::cli {

bool parseArgs(int argc, char** argv, int first, const std::set<std::string>& with_value,
               const std::set<std::string>& flags, Args* out, std::string* error) {
    for (int i = first; i < argc; ++i) {
        std::string a = argv[i];
        // Short options ("-o") are options only when the command declares them.
        const bool short_option = a.size() == 2 && a[0] == '-' && (with_value.count(a) || flags.count(a));
        if ((a.size() > 2 && a.rfind("--", 0) == 0) || short_option) {
            std::string value;
            bool inline_value = false;
            if (auto eq = a.find('='); eq != std::string::npos) {
                value = a.substr(eq + 1);
                a = a.substr(0, eq);
                inline_value = true;
            }
            if (with_value.count(a)) {
                if (!inline_value) {
                    if (i + 1 >= argc) {
                        *error = "option " + a + " needs a value";
                        return false;
                    }
                    value = argv[++i];
                }
                out->options[a] = value;
            } else if (flags.count(a) && !inline_value) {
                out->options[a] = "";
            } else {
                *error = "unknown option " + a;
                return false;
            }
        } else {
            out->positional.push_back(a);
        }
    }
    return true;
}

bool parseInt(const std::string& option, const std::string& text, long lo, long hi, long* out, std::string* error) {
    errno = 0;
    char* end = nullptr;
    long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || v < lo || v > hi) {
        *error = option + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" +
                 text + "'";
        return false;
    }
    *out = v;
    return true;
}

bool parseSize(const std::string& option, const std::string& text, long lo, long hi, int* width, int* height,
               std::string* error) {
    const size_t x = text.find('x');
    long w = 0, h = 0;
    if (x == std::string::npos || !parseInt(option, text.substr(0, x), lo, hi, &w, error) ||
        !parseInt(option, text.substr(x + 1), lo, hi, &h, error)) {
        *error = option + ": expected WIDTHxHEIGHT, each in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                 "], got '" + text + "'";
        return false;
    }
    *width = int(w);
    *height = int(h);
    return true;
}

bool parseNumberList(const std::string& option, const std::string& text, std::vector<double>* out, std::string* error) {
    out->clear();
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        size_t used = 0;
        double d = 0.0;
        try {
            d = std::stod(item, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(d)) {
            *error = option + ": '" + item + "' is not a finite number";
            return false;
        }
        out->push_back(d);
    }
    return true;
}

std::string assetsDir() {
    namespace fs = std::filesystem;
    if (const char* env = std::getenv("UG_ASSETS"); env && *env) return env;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        for (const fs::path& candidate : {exe.parent_path() / ".." / "assets", exe.parent_path() / ".." / ".." / "assets"})
            if (fs::exists(candidate / "models", ec)) return candidate.lexically_normal().string();
    }
    return std::string(UG_SOURCE_DIR) + "/assets";
}

std::string selfExecutablePath() {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("undergrowth") : p.string();
}

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

bool parseByteSize(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi, uint64_t* out,
                   std::string* error) {
    size_t digits = 0;
    while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
    const std::string unit = text.substr(digits);
    int shift = -1;
    if (unit.empty()) shift = 0;
    else if (unit == "K" || unit == "k") shift = 10;
    else if (unit == "M" || unit == "m") shift = 20;
    else if (unit == "G" || unit == "g") shift = 30;
    else if (unit == "T" || unit == "t") shift = 40;
    uint64_t value = 0;
    bool ok = digits > 0 && digits <= 15 && shift >= 0;
    if (ok) {
        value = std::stoull(text.substr(0, digits));
        ok = value <= (UINT64_MAX >> shift);
        value <<= shift;
    }
    if (!ok || value < lo || value > hi) {
        *error = option + ": '" + text + "' is not a size from " + std::to_string(lo) + " to " + std::to_string(hi) +
                 " bytes (a whole number, optionally with K, M, G or T)";
        return false;
    }
    *out = value;
    return true;
}

}  // namespace ug::cli
