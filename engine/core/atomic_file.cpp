#include "core/atomic_file.h"

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ug {

namespace {

std::string systemReason() { return std::strerror(errno); }

std::string hostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || !name[0]) return "host";
    std::string out;
    for (const char* c = name; *c; ++c) out += (std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_');
    return out;
}

// Temporary files are named ".<target>.tmp-<host>-<pid>-XXXXXX". A writer killed mid-write (kill -9, a
// power cut) leaves one behind, as large as the output; the next write of the same target removes it once
// its writer is known to be gone: same host and no such process, or (another host on a shared folder, or
// an older program's ".<target>.tmp-XXXXXX") untouched for longer than any write takes.
constexpr auto kForeignTempAge = std::chrono::hours(1);

void removeAbandonedTemporaries(const std::filesystem::path& dir, const std::string& target_name,
                                const std::string& host) {
    namespace fs = std::filesystem;
    const std::string prefix = "." + target_name + ".tmp-";
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string rest = name.substr(prefix.size());  // "<host>-<pid>-XXXXXX" or "XXXXXX"
        std::error_code file_ec;
        if (!it->is_regular_file(file_ec)) continue;
        bool abandoned = false;
        const size_t last = rest.rfind('-'), before = last == std::string::npos ? last : rest.rfind('-', last - 1);
        if (before != std::string::npos && rest.compare(0, before, host) == 0 && before == host.size()) {
            const std::string pid_text = rest.substr(before + 1, last - before - 1);
            char* stop = nullptr;
            const long pid = std::strtol(pid_text.c_str(), &stop, 10);
            abandoned = !pid_text.empty() && *stop == '\0' && pid > 0 && pid != long(::getpid()) &&
                        ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
        } else {
            const auto written = fs::last_write_time(it->path(), file_ec);
            abandoned = !file_ec && fs::file_time_type::clock::now() - written > kForeignTempAge;
        }
        if (abandoned) fs::remove(it->path(), file_ec);
    }
}

}  // namespace

bool writeFileAtomically(const std::string& path, const void* data, size_t size, std::string* error) {
    return writeFileAtomically(path, std::vector<ByteSpan>{ByteSpan{data, size}}, error);
}

bool writeFileAtomically(const std::string& path, const std::vector<ByteSpan>& parts, std::string* error) {
    namespace fs = std::filesystem;
    fs::path target(path);
    fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string host = hostName();
    removeAbandonedTemporaries(dir, target.filename().string(), host);
    std::string tmpl =
        (dir / ("." + target.filename().string() + ".tmp-" + host + "-" + std::to_string(::getpid()) + "-XXXXXX"))
            .string();
    std::vector<char> name(tmpl.begin(), tmpl.end());
    name.push_back('\0');
    int fd = mkstemp(name.data());
    if (fd < 0) {
        *error = path + ": cannot create a temporary file in '" + dir.string() + "': " + systemReason();
        return false;
    }
    for (const ByteSpan& part : parts) {
        const char* p = static_cast<const char*>(part.data);
        size_t left = part.size;
        while (left > 0) {
            ssize_t w = ::write(fd, p, left);
            if (w < 0) {
                if (errno == EINTR) continue;
                *error = path + ": write failed: " + systemReason();
                ::close(fd);
                ::unlink(name.data());
                return false;
            }
            p += w;
            left -= size_t(w);
        }
    }
    // The data must be on disk before the rename makes it visible, or a crash could leave an empty file
    // where the user's previous good one was.
    if (::fsync(fd) != 0 || ::fchmod(fd, 0644) != 0) {
        *error = path + ": flush failed: " + systemReason();
        ::close(fd);
        ::unlink(name.data());
        return false;
    }
    ::close(fd);
    if (std::rename(name.data(), path.c_str()) != 0) {
        *error = path + ": cannot replace the file: " + systemReason();
        ::unlink(name.data());
        return false;
    }
    return true;
}

bool writeTextFileAtomically(const std::string& path, const std::string& text, std::string* error) {
    return writeFileAtomically(path, text.data(), text.size(), error);
}

bool readWholeFile(const std::string& path, std::vector<unsigned char>* out, std::string* error, size_t max_bytes) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        *error = path + ": cannot open: " + systemReason();
        return false;
    }
    struct stat st {};
    if (::fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        *error = path + ": not a regular file";
        std::fclose(f);
        return false;
    }
    if (size_t(st.st_size) > max_bytes) {
        *error = path + ": " + std::to_string(st.st_size) + " bytes is larger than the limit of " +
                 std::to_string(max_bytes);
        std::fclose(f);
        return false;
    }
    out->resize(size_t(st.st_size));
    size_t got = out->empty() ? 0 : std::fread(out->data(), 1, out->size(), f);
    bool bad = std::ferror(f) != 0;
    std::fclose(f);
    if (bad || got != out->size()) {
        *error = path + ": read failed";
        return false;
    }
    return true;
}

bool readTextFile(const std::string& path, std::string* out, std::string* error, size_t max_bytes) {
    std::vector<unsigned char> bytes;
    if (!readWholeFile(path, &bytes, error, max_bytes)) return false;
    out->assign(bytes.begin(), bytes.end());
    return true;
}

}  // namespace ug
