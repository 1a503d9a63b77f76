#include "cli/cli_args.h"

#include <cerrno>
#include <cstdlib>
#include <filesystem>

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

}  // namespace ug::cli
