#include <gtest/gtest.h>

#include <algorithm>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <stdexcept>
#include <string>

#include "base/thread_pool.h"

namespace glint {
namespace {

TEST(ThreadPool, RunsEveryIndexExactlyOnce) {
    ThreadPool pool(2);
    std::vector<std::atomic<int>> runs(1000);
    pool.parallel_for(runs.size(), [&](size_t i) { ++runs[i]; });
    for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
}

TEST(ThreadPool, SeveralCallersShareThePool) {
    ThreadPool pool(2);
    std::atomic<long> total{0};
    std::vector<std::thread> callers;
    for (int c = 0; c < 4; ++c)
        callers.emplace_back([&] { pool.parallel_for(500, [&](size_t i) { total += long(i); }); });
    for (auto& t : callers) t.join();
    EXPECT_EQ(total.load(), 4L * 499 * 500 / 2);
}

TEST(ThreadPool, BatchesTakeTurns) {
    // One worker, two callers: once both batches wait, their tasks alternate (round-robin), so
    // a second job progresses while the first still has work.
    ThreadPool pool(1);
    std::mutex mutex;
    std::string order;
    std::promise<void> a_started, both_queued;
    std::shared_future<void> go = both_queued.get_future().share();
    auto record = [&](char c) {
        std::lock_guard lock(mutex);
        order += c;
    };
    std::thread a([&] {
        pool.parallel_for(5, [&](size_t i) {
            if (i == 0) {
                a_started.set_value();
                go.wait();
            }
            record('a');
        });
    });
    a_started.get_future().wait();
    std::thread b([&] { pool.parallel_for(5, [&](size_t) { record('b'); }); });
    while (pool.pending_batches() < 2) std::this_thread::yield();
    both_queued.set_value();
    a.join();
    b.join();
    EXPECT_EQ(order, "aababababb");
}

TEST(ThreadPool, TurnsFollowTheBatchesWeights) {
    // One worker held by a gate batch while batches of weight 1 and 3 arrive: once released, the
    // worker hands out three of the heavier batch's tasks for each of the lighter's, counted
    // over the tasks both still had, and a weight changed mid-batch takes effect at once.
    ThreadPool pool(1);
    std::mutex mutex;
    std::string order;
    std::promise<void> gate_started, release;
    std::shared_future<void> go = release.get_future().share();
    std::thread gate([&] {
        pool.parallel_for(1, [&](size_t) {
            gate_started.set_value();
            go.wait();
        });
    });
    gate_started.get_future().wait();
    std::atomic<double> light{1}, heavy{3};
    auto batch = [&](char c, std::atomic<double>* weight) {
        return std::thread([&, c, weight] {
            pool.parallel_for(40, [&, c](size_t) {
                std::lock_guard lock(mutex);
                order += c;
                if (order.size() == 40) light = 3;  // from here on, equal shares
            }, weight);
        });
    };
    std::thread a = batch('a', &light), b = batch('b', &heavy);
    while (pool.pending_batches() < 2) std::this_thread::yield();
    release.set_value();
    for (std::thread* t : {&gate, &a, &b}) t->join();
    ASSERT_EQ(order.size(), 80u);
    const auto count = [&](size_t from, size_t to, char c) { return std::count(order.begin() + from, order.begin() + to, c); };
    EXPECT_EQ(count(0, 40, 'b'), 30) << order;
    EXPECT_EQ(count(0, 40, 'a'), 10) << order;
    EXPECT_EQ(count(40, 60, 'a'), 10) << order;  // equal weights: round-robin
    EXPECT_EQ(count(40, 60, 'b'), 10) << order;
}

// The process's address space in use now, from /proc (its first field, in pages).
rlim_t address_space_in_use() {
    std::ifstream statm("/proc/self/statm");
    rlim_t pages = 0;
    statm >> pages;
    return pages * rlim_t(sysconf(_SC_PAGESIZE));
}

// A thread the system refuses (here: no address space left for its stack) ends the constructor
// in a runtime_error, after it joined the threads it had started, never in std::terminate. In a
// child process, so that the address-space limit cannot starve other tests.
TEST(ThreadPoolDeathTest, ARefusedThreadIsAnErrorNotAnAbort) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    GTEST_SKIP() << "the sanitizers reserve terabytes of address space: no limit on it can be set";
#endif
    EXPECT_EXIT(
        {
            rlimit limit{};
            getrlimit(RLIMIT_AS, &limit);
            limit.rlim_cur = address_space_in_use() + (rlim_t(64) << 20);  // a few 8 MiB stacks
            setrlimit(RLIMIT_AS, &limit);
            try {
                ThreadPool pool(ThreadPool::kMaxThreads);
            } catch (const std::runtime_error& e) {
                std::fprintf(stderr, "%s\n", e.what());
                std::_Exit(0);
            }
            std::_Exit(1);
        },
        ::testing::ExitedWithCode(0), "cannot start render thread [0-9]+ of 1024: ");
}

}  // namespace
}  // namespace glint
