#include "core/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ug {

namespace {
std::string systemReason() { return std::strerror(errno); }
}  // namespace

bool writeFileAtomically(const std::string& path, const void* data, size_t size, std::string* error) {
    return writeFileAtomically(path, std::vector<ByteSpan>{ByteSpan{data, size}}, error);
}

bool writeFileAtomically(const std::string& path, const std::vector<ByteSpan>& parts, std::string* error) {
    namespace fs = std::filesystem;
    fs::path target(path);
    fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::string tmpl = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
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

bool readTextFile(const std::string& path, std::string* out, std::string* error) {
    std::vector<unsigned char> bytes;
    if (!readWholeFile(path, &bytes, error, size_t(1) << 30)) return false;
    out->assign(bytes.begin(), bytes.end());
    return true;
}

}  // namespace ug
