// A job's progress as JSON: one schema for the API's status and the store's state.json.
#include <gtest/gtest.h>

#include "service/progress_json.h"

namespace glint {
namespace {

Progress some_progress() {
    Progress p;
    p.spp_done = 12;
    p.spp_target = 48;
    p.seconds = 1.5;
    p.samples_per_second = 2e6;
    p.error_estimate = 0.03125;
    p.dropped = 7;
    p.mean_spp = 9.5;
    p.pixels = 100;
    p.active_pixels = 40;
    return p;
}

void expect_same(const Progress& a, const Progress& b) {
    EXPECT_EQ(a.spp_done, b.spp_done);
    EXPECT_EQ(a.spp_target, b.spp_target);
    EXPECT_EQ(a.seconds, b.seconds);
    EXPECT_EQ(a.samples_per_second, b.samples_per_second);
    EXPECT_EQ(a.error_estimate, b.error_estimate);
    EXPECT_EQ(a.dropped, b.dropped);
    EXPECT_EQ(a.mean_spp, b.mean_spp);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.active_pixels, b.active_pixels);
}

TEST(ProgressJson, HasTheDocumentedFieldsAndReadsBack) {
    const nlohmann::json j = progress_json(some_progress());
    EXPECT_EQ(j.dump(),
              R"({"active_pixels":40,"dropped_samples":7,"elapsed":1.5,"error_estimate":0.03125,)"
              R"("mean_spp":9.5,"pixels":100,"samples_per_second":2000000.0,"spp_done":12,"spp_target":48})");
    expect_same(progress_from_json(j), some_progress());
}

TEST(ProgressJson, AnInfiniteEstimateIsNull) {
    Progress p = some_progress();
    p.error_estimate = kInfinity;
    const nlohmann::json j = progress_json(p);
    EXPECT_TRUE(j.at("error_estimate").is_null());
    EXPECT_EQ(progress_from_json(j).error_estimate, kInfinity);
}

TEST(ProgressJson, ReadsTheNamesOfOlderStores) {
    const auto j = nlohmann::json::parse(
        R"({"dropped":7,"seconds":1.5,"error_estimate":0.03125,"samples_per_second":2e6,)"
        R"("spp_done":12,"spp_target":48})");
    Progress older = some_progress();  // before adaptive sampling: every pixel had spp_done
    older.mean_spp = 12;
    older.pixels = older.active_pixels = 0;
    expect_same(progress_from_json(j), older);
}

TEST(ProgressJson, EtaIsTheTimeLeftAtTheRateSoFar) {
    EXPECT_EQ(eta_seconds(some_progress()), 1.5 * 36 / 12);
    EXPECT_EQ(eta_seconds(Progress{}), 0);
}

}  // namespace
}  // namespace glint
