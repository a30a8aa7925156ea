// The Slurm farm's poll, from the files its parts leave (no cluster needed): a film or an attempt
// is read only when its file changed, a requeued part is counted, a done part's partial file
// ends it, and a part's failure is its message.
#include <gtest/gtest.h>

#include "assembly/fingerprint.h"
#include "service/slurm_farm.h"
#include "support/image_files.h"
#include "support/test_support.h"

namespace glint {
namespace {

struct SlurmPollTest : ::testing::Test {
    testing::ScratchFolder folder{"glint-slurm-poll"};
    FarmRun run{"", "", folder.path(), {"0:4", "4:8"}};
    SlurmFarm farm{FarmConfig{}, folder.path()};
    std::vector<PartState> parts = std::vector<PartState>(2);

    std::vector<uint8_t> part_file(uint32_t first, uint32_t end) const {
        LoadedScene s = testing::small_cornell(end - first);
        s.settings.first_sample = first;
        return encode_partial(partial_of(*testing::render(s), 7, end - first));
    }
    void write(const std::string& name, const std::string& text) const {
        folder.write(name, std::vector<uint8_t>(text.begin(), text.end()));
    }
};

TEST_F(SlurmPollTest, AFileIsReadOnlyWhenItChanged) {
    const auto checkpoint = folder.path() / "part-0.checkpoint";
    folder.write("part-0.checkpoint", part_file(0, 2));
    FarmPoll found = farm.poll(run, parts);
    EXPECT_TRUE(found.films_changed);
    ASSERT_TRUE(parts[0].film);
    EXPECT_EQ(parts[0].film->end_sample, 2u);
    EXPECT_FALSE(parts[0].done);

    // Bytes that are no film, under the time already read: a poll that read them would throw.
    const auto time = std::filesystem::last_write_time(checkpoint);
    write("part-0.checkpoint", "not a film");
    std::filesystem::last_write_time(checkpoint, time);
    found = farm.poll(run, parts);
    EXPECT_FALSE(found.films_changed);
    EXPECT_EQ(parts[0].film->end_sample, 2u);
    EXPECT_EQ(found.counts.done, 0);
}

TEST_F(SlurmPollTest, CountsRequeuedAndDonePartsFromTheirFiles) {
    write("part-0.attempt", "1\n");
    write("part-1.attempt", "2\n");
    folder.write("part-1.partial", part_file(4, 8));
    const FarmPoll found = farm.poll(run, parts);
    EXPECT_TRUE(found.films_changed);
    EXPECT_EQ(found.counts.requeued, 1);
    EXPECT_EQ(found.counts.done, 1);
    EXPECT_TRUE(parts[1].done);
    EXPECT_EQ(parts[1].attempt, 2);
    EXPECT_EQ(found.counts.queued + found.counts.running, 0);  // no cluster answers squeue here
    EXPECT_FALSE(found.failure);
}

TEST_F(SlurmPollTest, AFailedPartIsItsMessage) {
    write("part-1.failed", "part 1 (samples 4:8, on node3) failed with exit code 1:\nno such mesh\n");
    const FarmPoll found = farm.poll(run, parts);
    ASSERT_TRUE(found.failure);
    EXPECT_EQ(*found.failure, "part 1 (samples 4:8, on node3) failed with exit code 1:\nno such mesh\n");
}

}  // namespace
}  // namespace glint
