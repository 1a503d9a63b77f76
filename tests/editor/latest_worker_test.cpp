// LatestWorker (editor/latest_worker.h): the editor's live jobs work on the newest submission, and a frame
// may wait a bounded time for a fresh edit's result. The work here is held on a gate the test opens, so
// every outcome is decided by the order of events, never by how fast the machine is.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "editor/latest_worker.h"

namespace ug::editor {
namespace {

using namespace std::chrono_literals;

// A gate the work waits at until the test opens it.
struct Gate {
    std::mutex mutex;
    std::condition_variable opened_cv;
    bool opened = false;
    std::atomic<int> entered{0};

    void pass() {
        ++entered;
        std::unique_lock<std::mutex> lock(mutex);
        opened_cv.wait(lock, [this] { return opened; });
    }
    void open() {
        {
            std::lock_guard<std::mutex> lock(mutex);
            opened = true;
        }
        opened_cv.notify_all();
    }
};

TEST(LatestWorker, WaitingForAResultTimesOutWhileTheWorkIsHeldAndReturnsItOnceDone) {
    Gate gate;
    LatestWorker<int, int> worker([&](const int& in) {
        gate.pass();
        return in * 10;
    });
    worker.submit(4);
    // Held at the gate: the bounded wait gives up with nothing to poll, and the worker is still busy.
    EXPECT_FALSE(worker.waitForResult(20ms));
    EXPECT_TRUE(worker.busy());
    int out = 0;
    EXPECT_FALSE(worker.poll(&out));
    gate.open();
    // Opened: the wait returns as soon as the result is there (the budget is only an upper bound).
    ASSERT_TRUE(worker.waitForResult(60s));
    ASSERT_TRUE(worker.poll(&out));
    EXPECT_EQ(out, 40);
    EXPECT_FALSE(worker.busy());
    // Nothing submitted: the wait returns at once, with nothing to poll.
    EXPECT_FALSE(worker.waitForResult(60s));
}

TEST(LatestWorker, ASubmissionNotStartedIsReplacedByTheNewestAndOnlyItsResultIsPolled) {
    Gate gate;
    LatestWorker<int, int> worker([&](const int& in) {
        if (in == 1) gate.pass();  // the first submission holds the worker while the next ones arrive
        return in;
    });
    worker.submit(1);
    while (gate.entered.load() == 0) std::this_thread::yield();
    worker.submit(2);
    worker.submit(3);  // replaces 2, which never starts
    gate.open();
    worker.waitIdle();
    int out = 0;
    ASSERT_TRUE(worker.poll(&out));
    EXPECT_EQ(out, 3);  // 1's result was replaced by 3's before the poll
    EXPECT_FALSE(worker.poll(&out));
}

}  // namespace
}  // namespace ug::editor
