#include <gtest/gtest.h>

#include <atomic>

#include "thread_pool.h"

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

}  // namespace
}  // namespace glint
