// The HTTP API against a real server on 127.0.0.1 and a free port, through cpp-httplib's client.
#include <gtest/gtest.h>

#include <thread>

#include <nlohmann/json.hpp>

#include "assembly/film_exr.h"
#include "denoise/denoiser.h"
#include "http/job_view.h"
#include "support/http_server_fixture.h"
#include "support/raw_http.h"
#include "support/test_support.h"

namespace glint {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::Server;
using testing::decode_png;
using testing::Decoded;
using testing::kSmallCornell;

// The scene of kSmallCornell, as the library loads it.
LoadedScene small_cornell() { return testing::small_cornell(16); }

TEST_F(Server, HealthAndPresets) {
    EXPECT_EQ(get_json("/health")["status"], "ok");
    const json presets = get_json("/presets");
    ASSERT_TRUE(presets.is_array());
    bool cornell = false;
    for (const auto& p : presets) cornell |= p["name"] == "cornell" && p["width"] == 1024;
    EXPECT_TRUE(cornell) << presets.dump();
    EXPECT_EQ(get_json("/presets/cornell")["camera"]["near"], 140);
    EXPECT_EQ(get_json("/presets/nope", 404)["error"], "no preset nope");
}

TEST_F(Server, RenderReturnsTheSamePngAsTheLibrary) {
    auto res = client_->Post("/render", kSmallCornell, "application/json");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
    const auto job = testing::render(small_cornell());
    const std::vector<uint8_t> expected = encode_png(job->film().mean(), Encoding::gamma22);
    EXPECT_EQ(res->body, std::string(expected.begin(), expected.end()));
}

TEST_F(Server, JobLifecycleAndImages) {
    const json accepted = post("/jobs", kSmallCornell, 202);
    const std::string id = accepted["id"];
    EXPECT_EQ(accepted["urls"]["stream"], "/jobs/" + id + "/stream");
    const json done = wait_until_final(id);
    EXPECT_EQ(done["state"], "done");
    EXPECT_EQ(done["spp_done"], 16);
    EXPECT_GT(done["samples_per_second"].get<double>(), 0);
    EXPECT_TRUE(done["error_estimate"].is_number());
    auto png = client_->Get(("/jobs/" + id + "/image.png").c_str());
    ASSERT_TRUE(png);
    EXPECT_EQ(decode_png(png->body).width, 40);
    auto pfm = client_->Get(("/jobs/" + id + "/image.pfm").c_str());
    ASSERT_TRUE(pfm);
    EXPECT_EQ(decode_pfm(std::vector<uint8_t>(pfm->body.begin(), pfm->body.end())).height, 30);
    bool listed = false;
    for (const auto& j : get_json("/jobs")) listed |= j["id"] == id;
    EXPECT_TRUE(listed);
}

// The EXR of a job with AOVs: OpenEXR's magic, its content type, and the bytes `glint render
// --exr` writes for the same render (the film's layers as the last frame published them).
TEST_F(Server, ImageExrIsTheFilmWithItsLayers) {
    const json accepted =
        post("/jobs", R"({"preset": "cornell", "width": 40, "height": 30, "spp": 16, "aovs": true})", 202);
    const std::string id = accepted["id"];
    EXPECT_EQ(accepted["urls"]["exr"], "/jobs/" + id + "/image.exr");
    EXPECT_EQ(wait_until_final(id)["state"], "done");
    auto exr = client_->Get(("/jobs/" + id + "/image.exr").c_str());
    ASSERT_TRUE(exr);
    EXPECT_EQ(exr->status, 200);
    EXPECT_EQ(exr->get_header_value("Content-Type"), "image/x-exr");
    EXPECT_EQ(exr->body.substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
    LoadedScene s = small_cornell();
    s.settings.aovs = true;
    const auto job = testing::render(s);
    const std::vector<uint8_t> expected = encode_film_exr(job->film().mean(), job->film());
    EXPECT_EQ(exr->body, std::string(expected.begin(), expected.end()));
    EXPECT_EQ(get_json("/jobs/0123456789abcdef/image.exr", 404)["error"], "no job 0123456789abcdef");
}

TEST_F(Server, ServesTheDenoisedPreviewBesideTheUnbiasedImage) {
    const std::string id = post("/jobs", kSmallCornell, 202)["id"];
    const json done = wait_until_final(id);
    EXPECT_EQ(done["urls"]["denoised"], "/jobs/" + id + "/image.denoised.png");
    auto res = client_->Get(("/jobs/" + id + "/image.denoised.png").c_str());
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
    ThreadPool pool(1);
    const auto job = testing::render(small_cornell());
    const std::vector<uint8_t> expected = encode_png(denoise(job->film(), pool), Encoding::gamma22);
    EXPECT_EQ(res->body, std::string(expected.begin(), expected.end()));
    EXPECT_NE(res->body, client_->Get(("/jobs/" + id + "/image.png").c_str())->body);  // the PNG stays unbiased
    EXPECT_EQ(client_->Get("/jobs/nope/image.denoised.png")->status, 404);
}

TEST_F(Server, BadInputGetsAStatusAndAJsonBody) {
    EXPECT_TRUE(post("/jobs", R"({"preset": )", 400)["error"].get<std::string>().starts_with("malformed JSON"));
    const json invalid = post("/jobs", R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]})", 422);
    EXPECT_EQ(invalid["path"], "objects[0].radius");
    EXPECT_EQ(invalid["error"], "must be > 0");
    EXPECT_EQ(post("/jobs", R"({"preset": "cornell", "spp": 100000000})", 422)["error"], "must be an integer in [1, 65536]");
    EXPECT_EQ(post("/jobs", R"({"film": {"width": 4096, "height": 4097}})", 422)["path"], "film.height");
    EXPECT_EQ(post("/jobs", R"({"preset": "../cornell"})", 404)["path"], "preset");
    EXPECT_EQ(post("/jobs", R"({"preset": "cornell", "colour": 1})", 422)["path"], "colour");
    EXPECT_EQ(get_json("/jobs/0123456789abcdef", 404)["error"], "no job 0123456789abcdef");
    EXPECT_EQ(get_json("/no/such/route", 404)["error"], "no such route or file");
    // Rejected requests leave no job behind.
    EXPECT_TRUE(get_json("/jobs").empty());
}

TEST_F(Server, OversizedBodiesGet413) {
    HttpConfig http;
    http.max_body_bytes = 1000;
    start({}, http);
    const json body = post("/jobs", R"({"description": ")" + std::string(5000, 'x') + R"("})", 413);
    EXPECT_EQ(body["error"], "request body too large");
}

TEST_F(Server, AFullQueueGets429WithRetryAfter) {
    ServiceConfig service;
    service.max_running = 1;
    service.max_queued = 1;
    start(service);
    const std::string slow = R"({"preset": "cornell", "width": 64, "height": 48, "spp": 65536})";
    const std::string first = post("/jobs", slow, 202)["id"];
    for (int i = 0; i < 500 && get_json("/jobs/" + first)["state"] == "queued"; ++i) std::this_thread::sleep_for(20ms);
    const std::string second = post("/jobs", slow, 202)["id"];  // waits in the queue
    auto res = client_->Post("/jobs", slow, "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 429);
    EXPECT_EQ(res->get_header_value("Retry-After"), "5");
    EXPECT_EQ(json::parse(res->body)["error"], "too many queued jobs (limit 1)");
    // The jobs in flight are untouched by the refusal; cancelling them works.
    EXPECT_EQ(get_json("/jobs/" + first)["state"], "running");
    EXPECT_EQ(client_->Get(("/jobs/" + second + "/image.exr").c_str())->status, 409);  // no frame yet
    EXPECT_EQ(client_->Delete(("/jobs/" + second).c_str())->status, 200);
    EXPECT_EQ(client_->Delete(("/jobs/" + first).c_str())->status, 200);
    EXPECT_EQ(wait_until_final(first)["state"], "cancelled");
    EXPECT_EQ(wait_until_final(second)["state"], "cancelled");
}

TEST_F(Server, CancelledJobsKeepWhatTheyRendered) {
    const std::string id = post("/jobs", R"({"preset": "cornell", "width": 64, "height": 48, "spp": 65536})", 202)["id"];
    for (int i = 0; i < 200 && get_json("/jobs/" + id)["spp_done"] == 0; ++i) std::this_thread::sleep_for(20ms);
    EXPECT_EQ(client_->Delete(("/jobs/" + id).c_str())->status, 200);
    const json s = wait_until_final(id);
    EXPECT_EQ(s["state"], "cancelled");
    EXPECT_GT(s["spp_done"].get<int>(), 0);
    EXPECT_EQ(decode_png(client_->Get(("/jobs/" + id + "/image.png").c_str())->body).width, 64);
}

// Splits a multipart/x-mixed-replace body into its parts' payloads.
std::vector<std::string> parts(const std::string& body) {
    std::vector<std::string> out;
    const std::string marker = "Content-Length: ";
    for (size_t at = body.find(marker); at != std::string::npos; at = body.find(marker, at)) {
        const size_t length = std::stoul(body.substr(at + marker.size()));
        const size_t start = body.find("\r\n\r\n", at) + 4;
        out.push_back(body.substr(start, length));
        at = start + length;
    }
    return out;
}

TEST_F(Server, StreamYieldsDecodablePngsOfTheRequestedSizeAndEnds) {
    const std::string id = post("/jobs", R"({"preset": "cornell", "width": 48, "height": 36, "spp": 64})", 202)["id"];
    auto res = client_->Get(("/jobs/" + id + "/stream").c_str());
    ASSERT_TRUE(res);
    EXPECT_EQ(res->get_header_value("Content-Type"), "multipart/x-mixed-replace; boundary=frame");
    const std::vector<std::string> pngs = parts(res->body);
    ASSERT_GE(pngs.size(), 2u);
    for (const std::string& png : pngs) {
        const Decoded d = decode_png(png);
        EXPECT_EQ(d.width, 48);
        EXPECT_EQ(d.height, 36);
    }
    EXPECT_TRUE(res->body.ends_with("--frame--\r\n"));
}

TEST_F(Server, EventsReportProgressThenDone) {
    const std::string id = post("/jobs", R"({"preset": "cornell", "width": 48, "height": 36, "spp": 64})", 202)["id"];
    auto res = client_->Get(("/jobs/" + id + "/events").c_str());
    ASSERT_TRUE(res);
    EXPECT_EQ(res->get_header_value("Content-Type"), "text/event-stream");
    EXPECT_NE(res->body.find("event: progress\ndata: {"), std::string::npos);
    const size_t done = res->body.find("event: done\ndata: ");
    ASSERT_NE(done, std::string::npos);
    const json last = json::parse(res->body.substr(done + 18, res->body.find('\n', done + 18) - done - 18));
    EXPECT_EQ(last["state"], "done");
    EXPECT_EQ(last["spp_done"], 64);
}

TEST_F(Server, AClientThatLeavesMidStreamIsCleanedUp) {
    const std::string id = post("/jobs", R"({"preset": "cornell", "width": 48, "height": 36, "spp": 65536})", 202)["id"];
    size_t received = 0;
    auto res = client_->Get(("/jobs/" + id + "/stream").c_str(), [&](const char*, size_t n) {
        received += n;
        return received < 100;  // hang up after the first bytes
    });
    EXPECT_FALSE(res);  // the client cancelled the transfer
    int open = 1;
    for (int i = 0; i < 100 && open != 0; ++i) {
        std::this_thread::sleep_for(50ms);
        open = get_json("/health")["open_streams"];
    }
    EXPECT_EQ(open, 0);
    EXPECT_EQ(get_json("/jobs/" + id)["state"], "running");  // watching is not owning
    client_->Delete(("/jobs/" + id).c_str());
}

TEST_F(Server, RenderClientThatGoesAwayCancelsItsJob) {
    // The client leaves once the response's headers have come, so the job exists by then however
    // slowly the server runs (a client that gave up after a fixed time could leave before the
    // server had read its request: seen under ThreadSanitizer).
    std::string id;
    {
        testing::RawConnection impatient(service_->port());
        const std::string body = R"({"preset": "cornell", "width": 64, "height": 48, "spp": 65536})";
        impatient.send("POST /render HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: " +
                       std::to_string(body.size()) + "\r\n\r\n" + body);
        const std::string headers = impatient.read_headers(60s);
        ASSERT_EQ(testing::status_of(headers), 200) << headers;
        const std::string field = "X-Glint-Job: ";
        const size_t at = headers.find(field);
        ASSERT_NE(at, std::string::npos) << headers;
        id = headers.substr(at + field.size(), 16);
    }
    EXPECT_EQ(wait_until_final(id)["state"], "cancelled");
}

TEST_F(Server, SeveralJobsAtOnceAllFinish) {
    std::vector<std::string> ids;
    for (int i = 0; i < 4; ++i)
        ids.push_back(post("/jobs", R"({"preset": "cornell", "width": 32, "height": 24, "spp": 32, "seed": )" +
                                        std::to_string(i) + "}",
                           202)["id"]);
    for (const auto& id : ids) EXPECT_EQ(wait_until_final(id)["state"], "done");
}

TEST_F(Server, ASmallJobIsNotStarvedBehindALargeOne) {
    const std::string large = post("/jobs", R"({"preset": "cornell", "width": 128, "height": 96, "spp": 65536})", 202)["id"];
    for (int i = 0; i < 200 && get_json("/jobs/" + large)["spp_done"] == 0; ++i) std::this_thread::sleep_for(20ms);
    const std::string small = post("/jobs", R"({"preset": "cornell", "width": 32, "height": 24, "spp": 16})", 202)["id"];
    // Both jobs render at once: the small one finishes while the large one (hours of work) is
    // still running. (That their tiles alternate is proven by ThreadPool.BatchesTakeTurns.)
    EXPECT_EQ(wait_until_final(small)["state"], "done");
    EXPECT_EQ(get_json("/jobs/" + large)["state"], "running");
    client_->Delete(("/jobs/" + large).c_str());
}

TEST_F(Server, ServesTheWebPage) {
    auto res = client_->Get("/");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_NE(res->body.find("<title>glint</title>"), std::string::npos);
    EXPECT_EQ(client_->Get("/../CMakeLists.txt")->status, 403);  // see test_guarded_server.cpp
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A scene's warnings (an OBJ material's texture, ...) travel with its job into every status.
TEST(JobView, TheStatusCarriesTheScenesWarnings) {
    LoadedScene scene = load_scene(GLINT_SCENES_DIR "/cornell.json");
    EXPECT_FALSE(job_status(Job("a", scene)).contains("warnings"));
    scene.warnings = {"objects[0].file: material \"paint\": ignored texture map_Kd wood.png"};
    EXPECT_EQ(job_status(Job("b", scene))["warnings"], nlohmann::json(scene.warnings));
}

}  // namespace
}  // namespace glint
