// What was asked of a job from outside while it runs: to cancel (it ends, keeping what it has
// rendered) or to suspend (it stops at its next pass boundary and stays in the store, to resume
// when the server starts again). Its runner reads the requests and can sleep until one comes.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace glint {

class JobControl {
public:
    void cancel() { request(cancelled_); }
    void suspend() { request(suspended_); }
    bool cancelled() const { return cancelled_; }
    bool suspended() const { return suspended_; }
    // Sleeps for `seconds`, or until cancel() or suspend() is called.
    void sleep(double seconds) const {
        std::unique_lock lock(mutex_);
        asked_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return cancelled_ || suspended_; });
    }

private:
    void request(std::atomic<bool>& flag) {
        {
            std::lock_guard lock(mutex_);
            flag = true;
        }
        asked_.notify_all();
    }

    std::atomic<bool> cancelled_{false}, suspended_{false};
    mutable std::mutex mutex_;
    mutable std::condition_variable asked_;
};

}  // namespace glint
