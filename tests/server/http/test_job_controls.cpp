// What a client controls of a job over HTTP: its stop conditions, its priority (at submission
// and by PATCH) and the window of the image it renders.
#include <algorithm>
#include <cstring>

#include "io/image_io.h"
#include "support/http_server_fixture.h"

namespace glint {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::Decoded;
using testing::decode_png;
using testing::Server;

const std::string kEndless = R"({"preset": "cornell", "width": 40, "height": 30, "spp": 65536)";

TEST_F(Server, EachStopConditionIsAskedForAndReported) {
    const json timed = post("/jobs", kEndless + R"(, "time_limit": 0.3})", 202);
    EXPECT_EQ(timed["time_limit"], 0.3);
    EXPECT_EQ(wait_until_final(timed["id"])["stop_reason"], "time_limit");
    const json target = post("/jobs", kEndless + R"(, "target_error": 0.05})", 202);
    EXPECT_EQ(wait_until_final(target["id"])["stop_reason"], "target_error");
    // In a scene's film, as in a scene file.
    const json scene = json::parse(client_->Get("/presets/cornell")->body);
    json film_timed = scene;
    film_timed["film"].update({{"width", 40}, {"height", 30}, {"spp", 65536}, {"time_limit", 0.2}});
    EXPECT_EQ(wait_until_final(post("/jobs", film_timed.dump(), 202)["id"])["stop_reason"], "time_limit");
    const json done = post("/jobs", testing::kSmallCornell, 202);
    EXPECT_EQ(done["stop_reason"], nullptr);
    EXPECT_EQ(wait_until_final(done["id"])["stop_reason"], "spp");
    const json cancelled = post("/jobs", kEndless + "}", 202);
    client_->Delete(("/jobs/" + cancelled["id"].get<std::string>()).c_str());
    EXPECT_EQ(wait_until_final(cancelled["id"])["stop_reason"], "cancelled");
}

TEST_F(Server, BadStopConditionsGetTheFilmsMessage) {
    const json negative = post("/jobs", kEndless + R"(, "time_limit": -1})", 422);
    EXPECT_EQ(negative["path"], "time_limit");
    EXPECT_EQ(negative["error"], "must be a finite number >= 0 (0: off)");
    const json word = post("/jobs", kEndless + R"(, "target_error": "low"})", 422);
    EXPECT_EQ(word["path"], "target_error");
    json scene = json::parse(client_->Get("/presets/cornell")->body);
    scene["film"]["time_limit"] = -2;
    const json in_film = post("/jobs", scene.dump(), 422);
    EXPECT_EQ(in_film["path"], "film.time_limit");
    EXPECT_EQ(in_film["error"], "must be a finite number >= 0 (0: off)");
}

// Which job runs, with one slot: the queued job of highest priority, as it is when the slot
// frees (a PATCH moves a queued job), whatever the order of submission.
TEST_F(Server, QueuedJobsStartByPriorityAsPatched) {
    ServiceConfig one;
    one.max_running = 1;
    start(one);
    const auto wait_running = [&](const std::string& id) {
        for (int i = 0; i < 1000 && get_json("/jobs/" + id)["state"] != "running"; ++i) std::this_thread::sleep_for(10ms);
        return get_json("/jobs/" + id)["state"] == "running";
    };
    // The blocker holds the slot before the others are queued: the queue hands a slot to the
    // highest priority waiting when it looks, so on a busy machine a blocker not yet started
    // would lose it to `high`.
    const std::string blocker = post("/jobs", kEndless + "}", 202)["id"];
    std::string running = blocker;
    ASSERT_TRUE(wait_running(running));
    const std::string low = post("/jobs", kEndless + R"(, "priority": -1})", 202)["id"];
    const std::string mid = post("/jobs", kEndless + R"(, "priority": 2})", 202)["id"];
    const std::string high = post("/jobs", kEndless + R"(, "priority": 5})", 202)["id"];
    const std::string patched = post("/jobs", kEndless + "}", 202)["id"];
    EXPECT_EQ(patch("/jobs/" + patched, R"({"priority": 3})", 200)["priority"], 3);
    for (const std::string& next : {high, patched, mid, low}) {
        client_->Delete(("/jobs/" + running).c_str());
        wait_until_final(running);
        ASSERT_TRUE(wait_running(next)) << "expected " << next << " to start after " << running;
        for (const std::string& other : {low, mid, high, patched})
            if (other != next) {
                EXPECT_NE(get_json("/jobs/" + other)["state"], "running");
            }
        running = next;
    }
    client_->Delete(("/jobs/" + running).c_str());
}

TEST_F(Server, PatchChangesOnlyTheLiveJobsPriority) {
    const std::string id = post("/jobs", kEndless + "}", 202)["id"];
    const std::string path = "/jobs/" + id;
    EXPECT_EQ(patch(path, R"({"priority": -4})", 200)["priority"], -4);
    EXPECT_EQ(get_json(path)["priority"], -4);
    EXPECT_EQ(patch(path, R"({"priority": 11})", 422)["path"], "priority");
    EXPECT_EQ(patch(path, R"({"colour": 1})", 422)["path"], "colour");
    patch(path, R"({"priority": )", 400);
    patch("/jobs/0123456789abcdef", R"({"priority": 1})", 404);
    client_->Delete(path.c_str());
    wait_until_final(id);
    patch(path, R"({"priority": 1})", 409);
    EXPECT_EQ(get_json(path)["priority"], -4);
}

TEST_F(Server, AScenesPriorityIsTheJobsNotTheScenes) {
    json scene = json::parse(client_->Get("/presets/cornell")->body);
    scene["film"].update({{"width", 16}, {"height", 12}, {"spp", 4}});
    scene["priority"] = 7;
    const json status = post("/jobs", scene.dump(), 202);
    EXPECT_EQ(status["priority"], 7);
    EXPECT_EQ(wait_until_final(status["id"])["state"], "done");
    scene["priority"] = 2.5;
    EXPECT_EQ(post("/jobs", scene.dump(), 422)["path"], "priority");
}

// A PFM's rows, bottom first, as floats.
std::vector<float> pfm_floats(const std::string& pfm, int& width, int& height) {
    float scale = 0;
    int consumed = 0;
    EXPECT_EQ(std::sscanf(pfm.c_str(), "PF\n%d %d\n%f\n%n", &width, &height, &scale, &consumed), 3);
    std::vector<float> v(size_t(width) * height * 3);
    std::memcpy(v.data(), pfm.data() + consumed, v.size() * sizeof(float));
    return v;
}

TEST_F(Server, ARegionJobRendersTheWholeRendersPixelsOfItsWindow) {
    const json whole = post("/jobs", R"({"preset": "cornell", "width": 40, "height": 30, "spp": 8})", 202);
    const json part = post("/jobs", R"({"preset": "cornell", "width": 40, "height": 30, "spp": 8, "region": [9, 6, 33, 19]})", 202);
    EXPECT_EQ(part["width"], 24);
    EXPECT_EQ(part["height"], 13);
    EXPECT_EQ(part["region"], json({{"x0", 9}, {"y0", 6}, {"x1", 33}, {"y1", 19}, {"full_width", 40}, {"full_height", 30}}));
    wait_until_final(whole["id"]);
    wait_until_final(part["id"]);
    const Decoded png = decode_png(client_->Get(("/jobs/" + part["id"].get<std::string>() + "/image.png").c_str())->body);
    EXPECT_EQ(png.width, 24);
    EXPECT_EQ(png.height, 13);
    int w = 0, h = 0, pw = 0, ph = 0;
    const auto a = pfm_floats(client_->Get(("/jobs/" + whole["id"].get<std::string>() + "/image.pfm").c_str())->body, w, h);
    const auto b = pfm_floats(client_->Get(("/jobs/" + part["id"].get<std::string>() + "/image.pfm").c_str())->body, pw, ph);
    ASSERT_EQ(pw, 24);
    for (int y = 6; y < 19; ++y)  // rows from the top; the PFM's from the bottom
        for (int x = 9; x < 33; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(a[(size_t(h - 1 - y) * w + x) * 3 + c], b[(size_t(ph - 1 - (y - 6)) * pw + (x - 9)) * 3 + c]);
    const json outside = post("/jobs", R"({"preset": "cornell", "width": 40, "height": 30, "region": [0, 0, 41, 30]})", 422);
    EXPECT_EQ(outside["path"], "region");
    EXPECT_EQ(post("/jobs", R"({"preset": "cornell", "region": [0, 0, 4]})", 422)["path"], "region");
}

TEST_F(Server, AThumbnailFitsTheListsBox) {
    const json status = post("/jobs", R"({"preset": "cornell", "width": 400, "height": 120, "spp": 4})", 202);
    wait_until_final(status["id"]);
    const Decoded thumb = decode_png(client_->Get(status["urls"]["thumbnail"].get<std::string>().c_str())->body);
    EXPECT_EQ(thumb.width, 100);  // 400 / 4: the least whole factor that fits 128 × 96
    EXPECT_EQ(thumb.height, 30);
}

}  // namespace
}  // namespace glint
