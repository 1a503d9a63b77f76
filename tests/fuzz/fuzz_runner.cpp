// Fork per batch: a child runs inputs in-process, one after another, and publishes which one it is on
// through shared memory; the parent is the watchdog. When a child dies (signal, sanitizer report,
// uncaught exception) or overstays (hang, memory), the parent knows the input from the shared index,
// rebuilds it from its number (inputs are a pure function of it), saves it, and starts a new child on the
// next input. So one run survives any number of crashes and hangs, and a clean batch costs one fork.
#include "fuzz_runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <cxxabi.h>
#include <exception>
#include <execinfo.h>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <map>
#include <sys/mman.h>
#include <sys/wait.h>
#include <typeinfo>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#include <sanitizer/common_interface_defs.h>
#define UG_FUZZ_SANITIZED 1
#endif
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace ug::fuzz {

namespace {

namespace fs = std::filesystem;

// Exit codes of a child that found something without dying of it.
constexpr int kExitMessage = 75;    // a rejection message that is empty or does not name the file
constexpr int kExitPromise = 76;    // an accepted result that breaks the reader's header
constexpr int kExitLeak = 77;       // LeakSanitizer found memory the input left behind
constexpr int kExitException = 78;  // an exception escaped the reader
constexpr int kExitLeakWindow = 79; // a leak somewhere in the last window of inputs (see runChild)

struct Shared {
    std::atomic<uint64_t> current;     // the input being run
    std::atomic<int64_t> started_ns;   // when it started (steady clock); 0 between inputs
    std::atomic<uint64_t> next;        // inputs before this one are finished
    std::atomic<uint64_t> accepted;
    std::atomic<uint64_t> rejected;
    std::atomic<uint64_t> slowest_ns;
    std::atomic<uint64_t> slowest_index;
    // The leak-check window: its first input and the counters before it, to run it again one by one.
    std::atomic<uint64_t> window_begin;
    std::atomic<uint64_t> window_accepted;
    std::atomic<uint64_t> window_rejected;
};

int64_t nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void printStack() {
#ifdef UG_FUZZ_SANITIZED
    __sanitizer_print_stack_trace();
#else
    void* frames[64];
    backtrace_symbols_fd(frames, backtrace(frames, 64), 2);
#endif
}

// Readers report errors by returning false; an escaping exception would take down the editor or the
// CLI. The handler runs at the throw site (nothing catches it, so nothing was unwound): its stack
// shows where the exception came from.
[[noreturn]] void onTerminate() {
    std::string type = "unknown", what;
    if (const std::type_info* t = abi::__cxa_current_exception_type()) {
        int status = 0;
        char* name = abi::__cxa_demangle(t->name(), nullptr, nullptr, &status);
        type = status == 0 && name ? name : t->name();
        std::free(name);
    }
    if (std::exception_ptr e = std::current_exception()) {
        try {
            std::rethrow_exception(e);
        } catch (const std::exception& x) {
            what = x.what();
        } catch (...) {
        }
    }
    std::fprintf(stderr, "uncaught exception: %s: %s\n", type.c_str(), what.c_str());
    printStack();
    std::fflush(stderr);
    _exit(kExitException);
}

struct Source {
    const Target& target;
    const Corpus& corpus;
    const RunOptions& options;
    uint64_t count() const { return options.replay.empty() ? options.runs : options.replay.size(); }
    std::string at(uint64_t i) const {
        return options.replay.empty() ? makeInput(target, corpus, options.seed, i) : readFile(options.replay[i]);
    }
};

// The child: inputs [begin, end) until the deadline; stdout and stderr go to the log, emptied before
// every input so that after a death it holds exactly that input's output (the sanitizer's report).
// A leak check costs milliseconds, more than most inputs, so it runs every `leak_every` inputs; a leak
// found there ends the child with kExitLeakWindow and the parent runs the window again checking after
// every input, which names the input that leaked.
[[noreturn]] void runChild(const Source& src, uint64_t begin, uint64_t end, int64_t deadline_ns, Shared* sh,
                           const std::string& input_path, int log_fd, uint64_t leak_every) {
    dup2(log_fd, 1);
    dup2(log_fd, 2);
    std::set_terminate(onTerminate);
    auto openWindow = [&](uint64_t i) {
        sh->window_begin = i;
        sh->window_accepted = sh->accepted.load();
        sh->window_rejected = sh->rejected.load();
    };
    openWindow(begin);
    for (uint64_t i = begin; i < end && nowNs() < deadline_ns; ++i) {
        sh->current = i;
        const int64_t t0 = nowNs();
        sh->started_ns = t0;
        std::fflush(nullptr);
        std::cout.flush();
        std::cerr.flush();
        if (ftruncate(log_fd, 0) != 0) _exit(70);
        writeFile(input_path, src.at(i));
        const Outcome o = src.target.run(input_path);
#ifdef __SANITIZE_ADDRESS__
        if (src.options.leak_check && ((i + 1 - begin) % leak_every == 0 || i + 1 == end) &&
            __lsan_do_recoverable_leak_check())
            _exit(leak_every == 1 ? kExitLeak : kExitLeakWindow);
#else
        (void)leak_every;
#endif
        if (!o.violation.empty()) {
            std::fprintf(stderr, "broken promise: %s\n", o.violation.c_str());
            _exit(kExitPromise);
        }
        if (o.accepted) {
            ++sh->accepted;
        } else {
            const std::string bad = checkMessage(src.target, input_path, o.message);
            if (!bad.empty()) {
                std::fprintf(stderr, "bad message: %s: '%s'\n", bad.c_str(), o.message.c_str());
                _exit(kExitMessage);
            }
            ++sh->rejected;
        }
        const uint64_t took = uint64_t(nowNs() - t0);
        if (took > sh->slowest_ns) {
            sh->slowest_ns = took;
            sh->slowest_index = i;
        }
        sh->started_ns = 0;
        sh->next = i + 1;
        if ((i + 1 - begin) % leak_every == 0) openWindow(i + 1);
    }
#ifdef __SANITIZE_ADDRESS__
    // Stopped by the deadline inside a window: its inputs still get their check.
    if (src.options.leak_check && sh->window_begin != sh->next && __lsan_do_recoverable_leak_check())
        _exit(leak_every == 1 ? kExitLeak : kExitLeakWindow);
#endif
    std::fflush(nullptr);
    _exit(0);  // not exit(): no static destructors, no at-exit leak check of the whole batch
}

uint64_t residentMb(pid_t pid) {
    char path[64];
    std::snprintf(path, sizeof(path), "/proc/%d/statm", int(pid));
    FILE* f = std::fopen(path, "r");
    if (!f) return 0;
    unsigned long size = 0, resident = 0;
    const int n = std::fscanf(f, "%lu %lu", &size, &resident);
    std::fclose(f);
    return n == 2 ? uint64_t(resident) * uint64_t(sysconf(_SC_PAGESIZE)) / (1024 * 1024) : 0;
}

enum class Kind { Crash, Hang, Sanitizer, Memory, Message, Promise };

const char* kindName(Kind k) {
    switch (k) {
        case Kind::Crash: return "crash";
        case Kind::Hang: return "hang";
        case Kind::Sanitizer: return "sanitizer";
        case Kind::Memory: return "memory";
        case Kind::Message: return "message";
        case Kind::Promise: return "promise";
    }
    return "?";
}

struct Failure {
    Kind kind;
    std::string headline;             // one line: what happened
    std::string signature;            // equal for the same bug (deduplication)
    std::vector<std::string> frames;  // the top of the stack, for the report
};

// "    #3 0x55d0c4 in ug::loadGhostTileCache(std::string const&, ...) /src/x.cpp:52" -> the function.
std::vector<std::string> stackFrames(const std::string& log) {
    std::vector<std::string> frames;
    size_t p = 0;
    while (p < log.size()) {
        size_t e = log.find('\n', p);
        if (e == std::string::npos) e = log.size();
        std::string line = log.substr(p, e - p);
        p = e + 1;
        const size_t hash = line.find_first_not_of(' ');
        if (hash == std::string::npos || line[hash] != '#') continue;
        const size_t in = line.find(" in ");
        if (in == std::string::npos) {
            // Unsymbolized ("#2 0x7f (/lib/libOpenMeshCore.so+0x1234)"): keep the module.
            const size_t paren = line.find('(');
            if (paren != std::string::npos) frames.push_back(line.substr(paren));
            continue;
        }
        frames.push_back(line.substr(in + 4));
        if (frames.size() >= 40) break;
        // Only the first stack of the report: a blank line or the next section ends it.
        if (p < log.size() && log[p] == '\n') break;
    }
    return frames;
}

// The function of a frame without arguments or location.
std::string frameFunction(std::string f) {
    for (size_t a; (a = f.find("(anonymous namespace)")) != std::string::npos;) f.replace(a, 21, "{anon}");
    // The argument list starts at the first '(' outside template brackets ("glm::vec<3, float,
    // (glm::qualifier)0>" has one inside).
    int angle = 0;
    for (size_t k = 1; k < f.size(); ++k) {
        if (f[k] == '<') ++angle;
        else if (f[k] == '>') --angle;
        else if (f[k] == '(' && angle <= 0) {
            f.resize(k);
            break;
        }
    }
    const size_t space = f.find(" /");
    if (space != std::string::npos) f.resize(space);
    if (f.size() > 120) f.resize(120);
    return f;
}

// Frames of the sanitizer runtime, the C library, the standard library and the harness say nothing about
// which reader went wrong; the first frames outside them do. Children run unsymbolized (see
// __asan_default_options), so a frame is either a function name or "(module+offset)".
bool interestingFrame(const std::string& frame) {
    // The harness's own frames (symbolized: their source is under tests/fuzz/).
    if (frame.find("/tests/fuzz/") != std::string::npos) return false;
    const std::string fn = frameFunction(frame);
    static const char* const kSkip[] = {"__asan", "__interceptor", "__sanitizer", "__ubsan", "__lsan", "__cxa",
                                        "__cxxabiv1", "__gnu_cxx", "std::", "void std::", "bool std::",
                                        "operator new", "operator delete", "malloc", "calloc", "realloc",
                                        "free", "mem", "str", "abort", "raise", "__GI", "__libc", "gsignal",
                                        "pthread", "__pthread", "ug::fuzz::", "main", "_start", "__restore_rt",
                                        "_Unwind", "__static", "__sighandler", "clone", "start_thread",
                                        "__assert"};
    static const char* const kSkipModules[] = {"libasan.so", "libubsan.so", "libc.so", "libstdc++.so",
                                               "libgcc_s.so", "ld-linux", "libm.so"};
    for (const char* s : kSkip)
        if (fn.rfind(s, 0) == 0) return false;
    if (fn.rfind("(", 0) == 0)
        for (const char* m : kSkipModules)
            if (fn.find(m) != std::string::npos) return false;
    return true;
}

std::string firstLineWith(const std::string& log, const std::string& needle) {
    const size_t p = log.find(needle);
    if (p == std::string::npos) return "";
    const size_t b = log.rfind('\n', p);
    const size_t e = log.find('\n', p);
    return log.substr(b == std::string::npos ? 0 : b + 1, (e == std::string::npos ? log.size() : e) - (b == std::string::npos ? 0 : b + 1));
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    if (from.empty()) return s;
    for (size_t p = 0; (p = s.find(from, p)) != std::string::npos; p += to.size()) s.replace(p, from.size(), to);
    return s;
}

// Digits, addresses and the temporary folder differ between two inputs hitting the same bug.
std::string normalize(std::string s, const std::string& work_dir) {
    s = replaceAll(s, work_dir, "<dir>");
    std::string out;
    for (char c : s) {
        if (c >= '0' && c <= '9') {
            if (out.empty() || out.back() != '#') out.push_back('#');
        } else {
            out.push_back(c);
        }
    }
    if (out.size() > 140) out.resize(140);
    return out;
}

Failure classify(int status, bool hang, bool memory, const std::string& log, const std::string& work_dir,
                 double timeout_s, uint64_t rss_mb) {
    Failure f;
    f.frames = stackFrames(log);
    std::string top;
    int picked = 0;
    for (const std::string& fr : f.frames) {
        if (!interestingFrame(fr)) continue;
        const std::string fn = frameFunction(fr);
        top += (picked ? " < " : "") + fn;
        if (++picked == 2) break;
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const std::string asan = firstLineWith(log, "ERROR: AddressSanitizer");
    const std::string lsan = firstLineWith(log, "ERROR: LeakSanitizer");
    const std::string ubsan = firstLineWith(log, "runtime error:");
    const std::string assertion = firstLineWith(log, "Assertion `");
    if (hang) {
        f.kind = Kind::Hang;
        f.headline = "no result after " + std::to_string(int(timeout_s)) + " s";
        f.signature = "hang: " + top;
    } else if (memory) {
        f.kind = Kind::Memory;
        f.headline = "resident memory above " + std::to_string(rss_mb) + " MB";
        f.signature = "memory: " + top;
    } else if (code == kExitMessage || code == kExitPromise) {
        f.kind = code == kExitMessage ? Kind::Message : Kind::Promise;
        f.headline = firstLineWith(log, code == kExitMessage ? "bad message:" : "broken promise:");
        std::string key = f.headline;
        if (code == kExitMessage) key = key.substr(0, key.find(": '"));  // the kind of complaint, not the text
        f.signature = normalize(key, work_dir);
    } else if (code == kExitException) {
        f.kind = Kind::Crash;
        f.headline = firstLineWith(log, "uncaught exception:");
        const std::string type = f.headline.substr(0, f.headline.find(": ", 20));  // "uncaught exception: T"
        f.signature = type + ": " + top;
    } else if (!assertion.empty()) {
        // A library built with its asserts on (Debian's OpenMesh) aborts on input it did not expect.
        f.kind = Kind::Crash;
        f.headline = assertion;
        f.signature = "assert: " + normalize(assertion.substr(assertion.find(": ") + 2), work_dir);
    } else if (!ubsan.empty()) {
        f.kind = Kind::Sanitizer;
        f.headline = ubsan;
        const std::string where = ubsan.substr(0, ubsan.find(": runtime error"));
        f.signature = "ubsan " + fs::path(where).filename().string() + ": " + normalize(ubsan.substr(ubsan.find("runtime error")), work_dir);
    } else if (!lsan.empty() || code == kExitLeak) {
        f.kind = Kind::Sanitizer;
        f.headline = lsan.empty() ? "leak" : lsan;
        // The leak's allocation stack follows the "Direct leak" line.
        const size_t d = log.find("leak of");
        const std::vector<std::string> lf = stackFrames(d == std::string::npos ? log : log.substr(d));
        std::string leak_top;
        int n = 0;
        for (const std::string& fr : lf) {
            if (!interestingFrame(fr)) continue;
            const std::string fn = frameFunction(fr);
            leak_top += (n ? " < " : "") + fn;
            if (++n == 2) break;
        }
        if (!lf.empty()) f.frames = lf;
        f.signature = "leak: " + leak_top;
    } else if (!asan.empty()) {
        // The SUMMARY line names the error class ("allocation-size-too-big", "heap-buffer-overflow").
        const std::string summary = firstLineWith(log, "SUMMARY: AddressSanitizer: ");
        const std::string what = (summary.empty() ? asan : summary).substr(
            (summary.empty() ? asan : summary).find("AddressSanitizer: ") + 18);
        const std::string type = what.substr(0, what.find(' '));
        // A deadly signal caught by ASan is a crash; everything else it reports is a memory error.
        const bool signal = type == "SEGV" || type == "BUS" || type == "FPE" || type == "ILL" || type == "ABRT" ||
                            type == "stack-overflow";
        f.kind = signal ? Kind::Crash : Kind::Sanitizer;
        f.headline = asan;
        f.signature = "asan " + type + ": " + top;
    } else {
        f.kind = Kind::Crash;
        if (WIFSIGNALED(status))
            f.headline = std::string("killed by signal ") + strsignal(WTERMSIG(status));
        else
            f.headline = "exit code " + std::to_string(code);
        f.signature = f.headline + ": " + top;
    }
    if (f.headline.size() > 300) f.headline.resize(300);
    return f;
}

struct Finding {
    Failure first;
    uint64_t count = 0;
    std::vector<std::string> saved;
};

// A child's output, bounded: a reader stuck in a loop can print warnings for the whole timeout
// (OpenMesh's "Unsupported keyword" at tens of MB/s). poll() keeps the first 64 KB and empties the file
// when it grows past 16 MB; the report at the end is what read() returns after the head.
class Log {
public:
    explicit Log(int fd) : fd_(fd) {}
    // `input`: the one the output belongs to; the child empties the file itself when it moves on.
    void poll(uint64_t input) {
        if (input != input_) {
            head_.clear();
            dropped_ = 0;
            input_ = input;
        }
        const off_t size = lseek(fd_, 0, SEEK_END);
        if (size < (off_t(16) << 20)) return;
        if (head_.empty()) head_ = readRange(0, 65536);
        dropped_ += uint64_t(size);
        if (ftruncate(fd_, 0) != 0) std::perror("ftruncate");
    }
    std::string read() const {
        const off_t size = lseek(fd_, 0, SEEK_END);
        const off_t tail = std::min<off_t>(size, off_t(256) << 10);
        std::string s = head_;
        if (dropped_ || size > tail)
            s += "\n[... " + std::to_string(dropped_ + uint64_t(size - tail)) + " bytes of output left out ...]\n";
        return s + readRange(size - tail, size_t(tail));
    }

private:
    std::string readRange(off_t at, size_t n) const {
        std::string s(n, '\0');
        const ssize_t got = pread(fd_, s.data(), n, at);
        s.resize(got > 0 ? size_t(got) : 0);
        return s;
    }
    int fd_;
    std::string head_;
    uint64_t dropped_ = 0;
    uint64_t input_ = 0;
};

// Stops a child that overstayed: SIGABRT first, so a sanitized child prints where it was (handle_abort=1),
// then SIGKILL if it does not go within a few seconds.
int stopChild(pid_t pid) {
    kill(pid, SIGABRT);
    int status = 0;
    for (int k = 0; k < 500; ++k) {
        if (waitpid(pid, &status, WNOHANG) == pid) return status;
        usleep(10000);
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return status;
}

// A fresh process replays a saved finding, for two reasons: full stacks (fast_unwind_on_malloc=0; the
// uninstrumented libraries have no frame pointers, so the fast unwinder stops at their first frame), and
// proof that the input fails on its own, not because of what the batch ran before it.
std::string rerunFresh(const Target& target, const std::string& file, double timeout_s, bool* reproduced,
                       bool* stopped_out) {
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    *reproduced = false;
    if (n <= 0) return "";
    self[n] = '\0';
    char tmpl[] = "/tmp/ug-fuzz-rerun-XXXXXX";
    const int fd = mkstemp(tmpl);
    if (fd < 0) return "";
    char work_tmpl[] = "/tmp/ug-fuzz-rerun-dir-XXXXXX";
    const char* work = mkdtemp(work_tmpl);
    if (!work) {
        close(fd);
        unlink(tmpl);
        return "";
    }
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(fd, 1);
        dup2(fd, 2);
        const char* env = std::getenv("ASAN_OPTIONS");
        const std::string asan =
            (env ? std::string(env) + ":" : "") + "symbolize=1:fast_unwind_on_malloc=0:malloc_context_size=40";
        setenv("ASAN_OPTIONS", asan.c_str(), 1);
        execl(self, self, target.name, "--replay", file.c_str(), "--in-process", "--work-dir", work,
              static_cast<char*>(nullptr));
        _exit(127);
    }
    int status = 0;
    const int64_t limit = nowNs() + int64_t(timeout_s * 1e9);
    bool stopped = false;
    Log out(fd);
    while (waitpid(pid, &status, WNOHANG) != pid) {
        out.poll(0);
        if (nowNs() > limit) {
            status = stopChild(pid);
            stopped = true;
            break;
        }
        usleep(5000);
    }
    *reproduced = stopped || !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    *stopped_out = stopped;
    const std::string log = out.read();
    close(fd);
    unlink(tmpl);
    std::error_code ec;
    fs::remove_all(work, ec);
    return log;
}

void copyData(const Corpus& corpus, const std::string& work) {
    if (corpus.data_dir.empty()) return;
    fs::copy(corpus.data_dir, fs::path(work) / "data", fs::copy_options::recursive);
}

struct ChildEnd {
    int status = 0;
    bool hang = false, memory = false, died = false;
};

// The watchdog: waits for the child, stopping it when its current input overstays or its memory grows
// past the bound. `last_progress`: when a progress line was last printed (null: none are).
ChildEnd watchChild(pid_t pid, Shared* sh, Log& log, const RunOptions& options, const char* name,
                    int64_t* last_progress) {
    ChildEnd e;
    while (true) {
        log.poll(sh->current);
        if (waitpid(pid, &e.status, WNOHANG) == pid) {
            e.died = !(WIFEXITED(e.status) && WEXITSTATUS(e.status) == 0);
            return e;
        }
        const int64_t started = sh->started_ns;
        if (started && nowNs() - started > int64_t(options.timeout_s * 1e9)) {
            e.hang = e.died = true;
            e.status = stopChild(pid);
            return e;
        }
        if (residentMb(pid) > options.rss_mb) {
            e.memory = e.died = true;
            e.status = stopChild(pid);
            return e;
        }
        if (last_progress && nowNs() - *last_progress > int64_t(20e9)) {
            *last_progress = nowNs();
            std::printf("fuzz %s: %llu inputs so far\n", name, (unsigned long long)sh->next.load());
            std::fflush(stdout);
        }
        usleep(2000);
    }
}

// A scratch folder holding the corpus's data/ and the path the input is written to.
// `given`: a folder made (and removed) by the caller, for a process that may die before its destructor
// runs (rerunFresh's replays are expected to crash).
struct Workspace {
    std::string dir, input_path;
    int log_fd = -1;
    bool make(const Target& target, const Corpus& corpus, const std::string& given = "") {
        char tmpl[] = "/tmp/ug-fuzz-XXXXXX";
        const char* made = given.empty() ? mkdtemp(tmpl) : given.c_str();
        if (!made) {
            std::perror("mkdtemp");
            return false;
        }
        dir = made;
        copyData(corpus, dir);
        input_path = dir + "/" + (std::string(target.name) == "scene" ? "scene" : "input") + target.ext;
        log_fd = open((dir + "/child.log").c_str(), O_RDWR | O_CREAT | O_TRUNC | O_APPEND, 0600);
        return log_fd >= 0;
    }
    ~Workspace() {
        if (log_fd >= 0) close(log_fd);
        if (!dir.empty()) fs::remove_all(dir);
    }
};

}  // namespace

int minimize(const Target& target, const Corpus& corpus, const std::string& file, const RunOptions& base_options,
             const std::string& out_path) {
    Workspace ws;
    if (!ws.make(target, corpus)) return 1;
    const std::string candidate = ws.dir + "/candidate";
    RunOptions options = base_options;
    options.replay = {candidate};
    const Source src{target, corpus, options};
    auto* sh = static_cast<Shared*>(
        mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
    uint64_t trials = 0;
    // One fork per trial, the file alone, leak checks after it: the same classification as a fuzz run.
    auto run = [&](const std::string& bytes, Failure* f) {
        writeFile(candidate, bytes);
        new (sh) Shared{};
        ++trials;
        std::fflush(nullptr);
        const pid_t pid = fork();
        if (pid == 0) runChild(src, 0, 1, nowNs() + int64_t(1e12), sh, ws.input_path, ws.log_fd, 1);
        Log log(ws.log_fd);
        const ChildEnd e = watchChild(pid, sh, log, options, target.name, nullptr);
        if (!e.died) return false;
        *f = classify(e.status, e.hang, e.memory, log.read(), ws.dir, options.timeout_s, options.rss_mb);
        return true;
    };
    std::string bytes = readFile(file);
    Failure first;
    if (!run(bytes, &first)) {
        std::printf("minimize %s: %s does not fail\n", target.name, file.c_str());
        munmap(sh, sizeof(Shared));
        return 1;
    }
    std::printf("minimize %s: %s, %zu bytes: %s\n  signature: %s\n", target.name, file.c_str(), bytes.size(),
                first.headline.c_str(), first.signature.c_str());
    const int64_t deadline = nowNs() + int64_t(options.seconds * 1e9);
    // Delta debugging by deletion: halves, then quarters, ... then single bytes; a deletion is kept when the
    // same finding (kind and signature) still happens.
    for (size_t chunk = std::max<size_t>(1, bytes.size() / 2); nowNs() < deadline; chunk /= 2) {
        for (size_t at = 0; at < bytes.size() && nowNs() < deadline;) {
            std::string shorter = bytes;
            shorter.erase(at, chunk);
            Failure f;
            if (run(shorter, &f) && f.kind == first.kind && f.signature == first.signature) bytes = shorter;
            else at += chunk;
        }
        if (chunk == 1) break;
    }
    writeFile(out_path, bytes);
    std::printf("minimize %s: %zu bytes after %llu trials%s: %s\n", target.name, bytes.size(),
                (unsigned long long)trials, nowNs() < deadline ? "" : " (stopped by --seconds)", out_path.c_str());
    munmap(sh, sizeof(Shared));
    return 0;
}

TargetResult fuzzTarget(const Target& target, const Corpus& corpus, const RunOptions& options) {
    TargetResult result;
    const Source src{target, corpus, options};
    const int64_t t_start = nowNs();
    const int64_t deadline = t_start + int64_t(options.seconds * 1e9);

    Workspace ws;
    if (!ws.make(target, corpus, options.work_dir)) return result;
    const std::string& work = ws.dir;
    const std::string& input_path = ws.input_path;
    const int log_fd = ws.log_fd;

    if (options.in_process) {
        // For a debugger: no fork, no watchdog; the first crash ends the run, as it should under gdb.
        std::set_terminate(onTerminate);
        for (uint64_t i = 0; i < src.count(); ++i) {
            writeFile(input_path, src.at(i));
            const Outcome o = target.run(input_path);
            ++result.inputs;
            std::printf("%s: %s%s%s\n", options.replay[i].c_str(), o.accepted ? "accepted" : "rejected: ",
                        o.accepted ? "" : o.message.c_str(),
                        o.violation.empty() ? "" : ("; BROKEN PROMISE: " + o.violation).c_str());
            if (!o.violation.empty()) ++result.promises;
            else if (o.accepted) ++result.accepted;
            else if (!checkMessage(target, input_path, o.message).empty()) ++result.messages;
            else ++result.rejected;
        }
        return result;
    }

    auto* sh = static_cast<Shared*>(
        mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
    new (sh) Shared{};
    std::map<std::string, Finding> findings;
    std::vector<std::string> order;  // signatures in the order first seen
    uint64_t next = 0;
    uint64_t precise_until = 0;  // inputs below this run with a leak check after each one
    constexpr uint64_t kLeakWindow = 64;
    int64_t last_progress = t_start;
    const std::string out_dir = options.out.empty() ? "" : (fs::path(options.out) / target.name).string();

    while (next < src.count() && nowNs() < deadline) {
        sh->next = next;
        sh->current = next;
        sh->started_ns = 0;
        std::fflush(nullptr);
        const pid_t pid = fork();
        if (pid < 0) {
            std::perror("fork");
            break;
        }
        const bool precise = next < precise_until;
        if (pid == 0)
            runChild(src, next, std::min(src.count(), precise ? precise_until : next + options.batch), deadline, sh,
                     input_path, log_fd, precise ? 1 : kLeakWindow);

        Log child_log(log_fd);
        const ChildEnd end = watchChild(pid, sh, child_log, options, target.name, &last_progress);
        const int status = end.status;
        const bool hang = end.hang, memory = end.memory, died = end.died;
        if (!died) {
            next = sh->next;
            continue;
        }
        if (WIFEXITED(status) && WEXITSTATUS(status) == kExitLeakWindow) {
            // Run the window again, one leak check per input, with its inputs counted once.
            next = sh->window_begin;
            sh->accepted = sh->window_accepted.load();
            sh->rejected = sh->window_rejected.load();
            precise_until = sh->current + 1;
            continue;
        }
        const uint64_t index = sh->current;
        const std::string log = child_log.read();
        const Failure f = classify(status, hang, memory, log, work, options.timeout_s, options.rss_mb);
        switch (f.kind) {
            case Kind::Crash: ++result.crashes; break;
            case Kind::Hang: ++result.hangs; break;
            case Kind::Sanitizer: ++result.sanitizer; break;
            case Kind::Memory: ++result.memory; break;
            case Kind::Message: ++result.messages; break;
            case Kind::Promise: ++result.promises; break;
        }
        Finding& finding = findings[f.signature];
        const bool fresh = finding.count++ == 0;
        if (fresh) {
            finding.first = f;
            order.push_back(f.signature);
        }
        std::string saved_as;
        std::vector<std::string> frames = f.frames;
        std::string reproduced_note;
        if (!out_dir.empty() && int(finding.saved.size()) < options.save_per_finding) {
            fs::create_directories(out_dir);
            const std::string base = (fs::path(out_dir) / (std::string(kindName(f.kind)) + "-" +
                                                           std::to_string(index))).string();
            saved_as = base + target.ext;
            writeFile(saved_as, src.at(index));
            std::string report = f.headline + "\nsignature: " + f.signature + "\n\n" + log;
            if (fresh && options.replay.empty()) {
                // A hang is only run long enough to see where it spins: seconds of CI time per hang.
                const double rerun_s = f.kind == Kind::Hang ? std::min(3.0, options.timeout_s) : options.timeout_s + 10.0;
                bool reproduced = false, stopped = false;
                const std::string again = rerunFresh(target, saved_as, rerun_s, &reproduced, &stopped);
                reproduced_note = !reproduced ? "NOT reproduced in a fresh process"
                                  : f.kind == Kind::Hang && stopped
                                      ? "still running after " + std::to_string(int(rerun_s)) + " s in a fresh process"
                                      : "reproduced in a fresh process";
                report += "\n---- " + reproduced_note + " (full stacks) ----\n" + again;
                const std::vector<std::string> full = stackFrames(again);
                if (reproduced && !full.empty()) frames = full;  // symbolized
            }
            writeFile(base + ".log", report);
            finding.saved.push_back(saved_as);
        }
        const std::string which =
            options.replay.empty() ? "input #" + std::to_string(index) : options.replay[index];
        if (fresh) {
            std::printf("FINDING fuzz %s %s (%s): %s\n", target.name, which.c_str(), kindName(f.kind),
                        f.headline.c_str());
            // The top frames, from the first one past the abort / terminate / signal machinery.
            static const char* const kNoise[] = {"__pthread_kill", "__GI_", "raise", "abort", "__assert",
                                                 "__sanitizer_print_stack_trace", "ug::fuzz::", "__cxxabiv1::",
                                                 "std::terminate", "(/lib/x86_64-linux-gnu/libstdc++"};
            size_t first = 0;
            auto noise = [&](const std::string& fr) {
                for (const char* n : kNoise)
                    if (fr.rfind(n, 0) == 0) return true;
                return false;
            };
            while (first < frames.size() && noise(frames[first])) ++first;
            if (first == frames.size()) first = 0;
            for (size_t k = first; k < frames.size() && k < first + 8; ++k) std::printf("    %s\n", frames[k].c_str());
            if (!saved_as.empty())
                std::printf("  saved as %s%s%s; replay: %s %s --replay %s\n", saved_as.c_str(),
                            reproduced_note.empty() ? "" : ", ", reproduced_note.c_str(), options.self_path.c_str(),
                            target.name, saved_as.c_str());
            std::fflush(stdout);
        }
        next = index + 1;
        if (!options.keep_going) break;
    }
    result.inputs = next;
    result.accepted = sh->accepted;
    result.rejected = sh->rejected;
    result.slowest_s = double(sh->slowest_ns.load()) * 1e-9;
    result.slowest_index = sh->slowest_index;
    result.findings = findings.size();
    result.seconds = double(nowNs() - t_start) * 1e-9;
    for (size_t k = 0; k < order.size(); ++k) {
        const Finding& f = findings[order[k]];
        std::printf("  finding %zu of %s: %s x%llu: %s%s%s\n", k + 1, target.name, kindName(f.first.kind),
                    (unsigned long long)f.count, f.first.signature.c_str(), f.saved.empty() ? "" : " (first: ",
                    f.saved.empty() ? "" : (f.saved.front() + ")").c_str());
    }
    munmap(sh, sizeof(Shared));
    return result;
}

}  // namespace ug::fuzz
