// `glint serve --store`: real server processes on 127.0.0.1 and free ports, killed with SIGKILL
// or stopped with SIGTERM and restarted on the same folder.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <httplib.h>

#include "assembly/fingerprint.h"
#include "assembly/partial_file.h"
#include "base/files.h"
#include "http/job_request.h"
#include "io/image_io.h"
#include "service/service_config.h"
#include "support/test_support.h"

extern char** environ;

namespace glint {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using nlohmann::json;

int free_port() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof address;
    bind(fd, reinterpret_cast<sockaddr*>(&address), size);
    getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
    close(fd);
    return ntohs(address.sin_port);
}

std::string read_text(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `glint serve --store DIR ...` as a child process, its log in a file.
class ServerProcess {
public:
    ServerProcess(const fs::path& store, const fs::path& log, std::vector<std::string> extra = {}) : log_(log) {
        port_ = free_port();
        std::vector<std::string> args = {GLINT_BINARY, "serve", "--port", std::to_string(port_), "--threads", "2",
                                         "--scenes", GLINT_SCENES_DIR, "--web", GLINT_WEB_DIR, "--store", store.string()};
        args.insert(args.end(), extra.begin(), extra.end());
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t files;
        posix_spawn_file_actions_init(&files);
        posix_spawn_file_actions_addopen(&files, 2, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        posix_spawn_file_actions_adddup2(&files, 2, 1);
        EXPECT_EQ(posix_spawn(&pid_, argv[0], &files, nullptr, argv.data(), environ), 0);
        posix_spawn_file_actions_destroy(&files);
        client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
        client_->set_read_timeout(30, 0);
        for (int i = 0; i < 1500 && !client_->Get("/health"); ++i) std::this_thread::sleep_for(20ms);
    }
    ~ServerProcess() {
        if (pid_ > 0) kill_now();
    }

    void kill_now() {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        pid_ = -1;
    }
    // SIGTERM; the exit status (0 when the server stopped cleanly).
    int stop() {
        kill(pid_, SIGTERM);
        int status = 0;
        waitpid(pid_, &status, 0);
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }

    httplib::Client& http() { return *client_; }
    json get_json(const std::string& path) {
        auto res = client_->Get(path.c_str());
        if (!res) return {};
        return json::parse(res->body);
    }
    std::string submit(const std::string& body) {
        auto res = client_->Post("/jobs", body, "application/json");
        EXPECT_TRUE(res && res->status == 202) << (res ? res->body : "no answer");
        return res && res->status == 202 ? json::parse(res->body)["id"].get<std::string>() : "";
    }
    json wait_until_final(const std::string& id) {
        for (int i = 0; i < 6000; ++i) {
            const json s = get_json("/jobs/" + id);
            if (s.is_object() && s["state"] != "queued" && s["state"] != "running") return s;
            std::this_thread::sleep_for(20ms);
        }
        ADD_FAILURE() << "job " << id << " did not finish";
        return {};
    }
    std::string get_body(const std::string& path, int expected_status = 200) {
        auto res = client_->Get(path.c_str());
        EXPECT_TRUE(res) << path;
        if (!res) return "";
        EXPECT_EQ(res->status, expected_status) << path << ": " << res->body;
        return res->body;
    }
    std::string log() const { return read_text(log_); }

private:
    fs::path log_;
    int port_ = 0;
    pid_t pid_ = -1;
    std::unique_ptr<httplib::Client> client_;
};

class Store : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        work_ = fs::temp_directory_path() / ("glint-store-" + std::string(test->name()) + "-" + std::to_string(getpid()));
        fs::remove_all(work_);
        fs::create_directories(work_);
        store_ = work_ / "store";
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(work_);
    }
    fs::path log(int n) const { return work_ / ("server" + std::to_string(n) + ".log"); }
    fs::path film(const std::string& id, const char* name) const { return store_ / id / name; }
    // Waits until the job has a checkpoint on disk (a whole pass or more).
    bool wait_for_checkpoint(const std::string& id) const {
        for (int i = 0; i < 3000; ++i) {
            if (fs::exists(film(id, "checkpoint.glntpart"))) return true;
            std::this_thread::sleep_for(10ms);
        }
        return false;
    }

    fs::path work_, store_;
};

// The images an uninterrupted render of the request gives, through the library.
std::pair<std::string, std::string> uninterrupted(const std::string& request) {
    const LoadedScene scene = parse_job_request(request, GLINT_SCENES_DIR, ServiceConfig{}.scene).scene;
    const auto job = testing::render(scene, 2);
    const Image image = job->film().mean();
    const auto png = encode_png(image, scene.settings.encoding), pfm = encode_pfm(image);
    return {std::string(png.begin(), png.end()), std::string(pfm.begin(), pfm.end())};
}

// The property the store rests on: a job resumed from a film of whole passes adds the remaining
// samples in the order an uninterrupted run does.
TEST(StoreResume, ARenderResumedBetweenPassesHasBitIdenticalSums) {
    LoadedScene scene = parse_job_request(R"({"preset": "cornell", "width": 12, "height": 8, "spp": 24})",
                                          GLINT_SCENES_DIR, ServiceConfig{}.scene).scene;
    ThreadPool pool(2);
    RenderJob whole(scene.scene, scene.settings);
    whole.run(pool);
    RenderSettings first_part = scene.settings;
    first_part.spp = 8;
    RenderJob before(scene.scene, first_part);
    before.run(pool);
    RenderJob resumed(scene.scene, scene.settings);
    resumed.resume(before.film(), 8);
    resumed.run(pool);
    ASSERT_EQ(resumed.progress().spp_done, 24u);
    for (size_t i = 0; i < whole.film().pixels().size(); ++i) {
        const PixelSums &a = whole.film().pixels()[i], &b = resumed.film().pixels()[i];
        ASSERT_EQ(std::memcmp(&a.sum, &b.sum, sizeof a.sum), 0) << "pixel " << i;
        ASSERT_EQ(std::memcmp(&a.half_sum, &b.half_sum, sizeof a.half_sum), 0) << "pixel " << i;
        ASSERT_EQ(a.count, b.count);
        ASSERT_EQ(a.half_count, b.half_count);
    }
    RenderJob wrong(scene.scene, scene.settings);
    EXPECT_THROW(wrong.resume(Film(4, 4), 8), std::invalid_argument);
    EXPECT_THROW(wrong.resume(before.film(), 6), std::invalid_argument);  // not whole rounds of 4
    EXPECT_THROW(wrong.resume(before.film(), 28), std::invalid_argument);  // beyond the job
}

uint32_t spp_done(ServerProcess& server, const std::string& id) {
    return server.get_json("/jobs/" + id)["spp_done"].get<uint32_t>();
}

TEST_F(Store, AJobSurvivesSigkillAndSigtermAndEndsBitIdenticalToAnUninterruptedRender) {
    const std::string request = R"({"preset": "cornell", "width": 40, "height": 30, "spp": 1200, "seed": 7})";
    std::string id;
    {
        ServerProcess server(store_, log(1), {"--checkpoint-interval", "0"});
        id = server.submit(request);
        ASSERT_TRUE(wait_for_checkpoint(id));
        server.kill_now();
    }
    const Partial killed_at = decode_partial(read_file(film(id, "checkpoint.glntpart").string(), SIZE_MAX));
    ASSERT_LT(killed_at.end_sample, 1200u) << "the job ended before the kill: make it longer";
    {
        ServerProcess server(store_, log(2), {"--checkpoint-interval", "0"});
        const json listed = server.get_json("/jobs");
        ASSERT_EQ(listed.size(), 1u);
        EXPECT_EQ(listed[0]["id"], id);
        EXPECT_GE(listed[0]["spp_done"].get<uint32_t>(), killed_at.end_sample) << "resumed, not restarted";
        // Then a graceful stop mid-render: the job is suspended at a pass, not cancelled.
        for (int i = 0; i < 3000 && spp_done(server, id) <= killed_at.end_sample; ++i) std::this_thread::sleep_for(10ms);
        EXPECT_EQ(server.stop(), 0);
    }
    EXPECT_NE(read_text(log(2)).find("job " + id + " resumes from its checkpoint at " +
                                     std::to_string(killed_at.end_sample) + " spp"),
              std::string::npos)
        << read_text(log(2));
    const auto [png, pfm] = uninterrupted(request);
    {
        ServerProcess server(store_, log(3));
        EXPECT_EQ(server.wait_until_final(id)["state"], "done");
        EXPECT_EQ(spp_done(server, id), 1200u);
        EXPECT_TRUE(server.get_body("/jobs/" + id + "/image.png") == png) << "PNG differs from an uninterrupted render";
        EXPECT_TRUE(server.get_body("/jobs/" + id + "/image.pfm") == pfm) << "PFM differs from an uninterrupted render";
        EXPECT_EQ(server.stop(), 0);
    }
    EXPECT_NE(read_text(log(2)).find("job " + id + " suspended"), std::string::npos);
    // A finished job is served again after a restart, from its final film alone.
    EXPECT_TRUE(fs::exists(film(id, "final.glntpart")));
    EXPECT_FALSE(fs::exists(film(id, "checkpoint.glntpart")));
    ServerProcess server(store_, log(4));
    EXPECT_EQ(server.get_json("/jobs/" + id)["state"], "done");
    EXPECT_TRUE(server.get_body("/jobs/" + id + "/image.png") == png);
    EXPECT_TRUE(server.get_body("/jobs/" + id + "/image.pfm") == pfm);
}

void flip_a_byte(const fs::path& file) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(std::streamoff(fs::file_size(file) / 2));
    const char c = char(f.get() ^ 0x40);
    f.seekp(std::streamoff(fs::file_size(file) / 2));
    f.put(c);
}

// The bytes the store has committed. A checkpoint being written (".tmp", renamed over the old
// one a moment later: the running job here checkpoints after every pass) is not part of the
// store yet, and it may vanish while it is counted.
uint64_t bytes_in(const fs::path& folder) {
    uint64_t total = 0;
    std::error_code error;
    for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
        std::error_code gone;
        if (it->path().extension() == ".tmp" || !it->is_regular_file(gone)) continue;
        const uintmax_t size = it->file_size(gone);
        if (!gone) total += size;
    }
    return total;
}

TEST_F(Store, CorruptOrTruncatedFilmsFailTheirJobsAndServeNoImage) {
    const std::string small = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 8})";
    const std::string endless = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 65536})";
    std::string done, flipped, truncated;
    {
        ServerProcess server(store_, log(1), {"--checkpoint-interval", "0"});
        done = server.submit(small);
        EXPECT_EQ(server.wait_until_final(done)["state"], "done");
        flipped = server.submit(endless);
        truncated = server.submit(endless);
        ASSERT_TRUE(wait_for_checkpoint(flipped));
        ASSERT_TRUE(wait_for_checkpoint(truncated));
        server.kill_now();
    }
    flip_a_byte(film(done, "final.glntpart"));
    flip_a_byte(film(flipped, "checkpoint.glntpart"));
    fs::resize_file(film(truncated, "checkpoint.glntpart"), fs::file_size(film(truncated, "checkpoint.glntpart")) / 2);
    // A state file cut short, and a temporary file a crash left behind.
    const std::string unreadable = "0123456789abcdef";
    fs::create_directories(store_ / unreadable);
    std::ofstream(store_ / unreadable / "request.json") << small;
    std::ofstream(store_ / unreadable / "state.json") << R"({"created": 1, "sta)";
    std::ofstream(store_ / done / "state.json.tmp") << "{";

    ServerProcess server(store_, log(2));
    EXPECT_EQ(server.get_json("/health")["status"], "ok");
    const std::pair<std::string, const char*> damaged[] = {
        {done, "final.glntpart"}, {flipped, "checkpoint.glntpart"}, {truncated, "checkpoint.glntpart"}};
    for (const auto& [id, file] : damaged) {
        const json status = server.get_json("/jobs/" + id);
        EXPECT_EQ(status["state"], "failed") << status.dump();
        const std::string error = status.value("error", "");
        EXPECT_NE(error.find(film(id, file).string() + ": checksum mismatch"), std::string::npos) << error;
        server.get_body("/jobs/" + id + "/image.png", 409);
        server.get_body("/jobs/" + id + "/image.pfm", 409);
        EXPECT_NE(server.log().find("job " + id + " failed: " + film(id, file).string()), std::string::npos);
    }
    server.get_body("/jobs/" + unreadable, 404);
    EXPECT_NE(server.log().find("job " + unreadable + " left out"), std::string::npos);
    EXPECT_FALSE(fs::exists(store_ / done / "state.json.tmp"));
    // The server goes on working, and the failure is kept: a restart does not read the files again.
    const std::string next = server.submit(small);
    EXPECT_EQ(server.wait_until_final(next)["state"], "done");
    EXPECT_EQ(server.stop(), 0);
    ServerProcess again(store_, log(3));
    EXPECT_EQ(again.get_json("/jobs/" + flipped)["state"], "failed");
    EXPECT_EQ(again.get_json("/jobs/" + next)["state"], "done");
}

// A film as a glint from before the sampler's replicates wrote it: partial file version 3 (no
// sampler version, rounds' sums of squares where version 4 keeps the first half's sums).
std::vector<uint8_t> as_version_three(const Partial& p) {
    std::vector<uint8_t> bytes;
    auto put = [&](const auto& v) {
        const auto* b = reinterpret_cast<const uint8_t*>(&v);
        bytes.insert(bytes.end(), b, b + sizeof v);
    };
    for (char c : std::string("GLNTPART")) put(c);
    for (uint32_t v : {3u, uint32_t(p.film.width()), uint32_t(p.film.height()), p.first_sample, p.end_sample,
                       uint32_t(p.encoding == Encoding::srgb)})
        put(v);
    put(p.fingerprint);
    for (const PixelSums& px : p.film.pixels()) {
        for (int c = 0; c < 3; ++c) put(px.sum[c]);
        for (int c = 0; c < 3; ++c) put(px.sum[c] * px.sum[c]);
        for (uint64_t v : {px.count, px.count / 4, px.dropped}) put(v);
        for (int64_t v : px.splat) put(v);
        for (int64_t v : px.splat_sq) put(v);
        put(px.splats_dropped);
    }
    Fnv1a h;
    h.bytes(bytes.data(), bytes.size());
    put(h.digest());
    return bytes;
}

// An upgrade loses nothing rendered: a finished job whose film an older glint wrote is served
// as it was; an unfinished one cannot go on with other sample points, and fails saying so.
TEST_F(Store, FilmsOfAnOlderSamplerAreServedButNotResumed) {
    std::string done, running;
    std::string png;
    {
        ServerProcess server(store_, log(1), {"--checkpoint-interval", "0"});
        done = server.submit(R"({"preset": "cornell", "width": 16, "height": 12, "spp": 8})");
        EXPECT_EQ(server.wait_until_final(done)["state"], "done");
        png = server.get_body("/jobs/" + done + "/image.png");
        running = server.submit(R"({"preset": "cornell", "width": 16, "height": 12, "spp": 65536})");
        ASSERT_TRUE(wait_for_checkpoint(running));
        server.kill_now();
    }
    for (const auto& [id, file] : {std::pair{done, "final.glntpart"}, std::pair{running, "checkpoint.glntpart"}}) {
        const fs::path path = film(id, file);
        write_file(path.string(), as_version_three(decode_partial(read_file(path.string(), SIZE_MAX))));
    }
    ServerProcess server(store_, log(2));
    EXPECT_EQ(server.get_json("/jobs/" + done)["state"], "done");
    EXPECT_TRUE(server.get_body("/jobs/" + done + "/image.png") == png);
    const json status = server.get_json("/jobs/" + running);
    EXPECT_EQ(status["state"], "failed") << status.dump();
    EXPECT_NE(status.value("error", "").find("another version of glint's sampler (1, not " + std::to_string(kSamplerVersion) + ")"), std::string::npos)
        << status.dump();
}

TEST_F(Store, EvictsTheOldestFinishedJobsBeyondItsLimitNeverAnUnfinishedOne) {
    const std::string small = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 4})";
    const uint64_t limit = 4 * partial_file_size(16, 12);
    ServerProcess server(store_, log(1), {"--store-limit", std::to_string(limit), "--checkpoint-interval", "0"});
    const std::string running = server.submit(R"({"preset": "cornell", "width": 16, "height": 12, "spp": 65536})");
    ASSERT_TRUE(wait_for_checkpoint(running));
    std::vector<std::string> finished;
    for (int i = 0; i < 6; ++i) {
        finished.push_back(server.submit(small));
        EXPECT_EQ(server.wait_until_final(finished.back())["state"], "done");
    }
    EXPECT_EQ(server.get_json("/jobs/" + running)["state"], "running");
    EXPECT_TRUE(fs::exists(store_ / running));
    server.get_body("/jobs/" + finished.front(), 404);
    EXPECT_FALSE(fs::exists(store_ / finished.front()));
    EXPECT_EQ(server.get_json("/jobs/" + finished.back())["state"], "done");
    EXPECT_TRUE(fs::exists(store_ / finished.back() / "final.glntpart"));
    EXPECT_LE(bytes_in(store_), limit);
    const std::string log_text = server.log();
    EXPECT_NE(log_text.find("limit " + std::to_string(limit) + " bytes"), std::string::npos) << log_text;
    EXPECT_NE(log_text.find("evicted finished job " + finished.front()), std::string::npos) << log_text;
    EXPECT_EQ(log_text.find("[error]"), std::string::npos) << log_text;
    // A job whose film alone would not fit is refused.
    auto res = server.http().Post("/jobs", R"({"preset": "cornell", "width": 64, "height": 48, "spp": 4})",
                                  "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 422);
    EXPECT_NE(res->body.find("would not fit in the store"), std::string::npos) << res->body;
    EXPECT_EQ(server.stop(), 0);
}

// A priority changed by PATCH, and why a job stopped, are the store's too: a restarted server
// starts the queued jobs in the order the priorities say and reports the ended ones as they were.
TEST_F(Store, PrioritiesAndStopReasonsSurviveARestart) {
    const std::string endless = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 65536)";
    std::string timed, blocker, low, high;
    {
        ServerProcess server(store_, log(1), {"--max-jobs", "1"});
        timed = server.submit(endless + R"(, "time_limit": 0.2})");
        EXPECT_EQ(server.wait_until_final(timed)["stop_reason"], "time_limit");
        blocker = server.submit(endless + "}");
        low = server.submit(endless + R"(, "priority": 1})");
        high = server.submit(endless + "}");
        auto res = server.http().Patch(("/jobs/" + high).c_str(), R"({"priority": 6})", "application/json");
        ASSERT_TRUE(res && res->status == 200);
        server.kill_now();
    }
    ServerProcess server(store_, log(2), {"--max-jobs", "1"});
    EXPECT_EQ(server.get_json("/jobs/" + timed)["stop_reason"], "time_limit");
    EXPECT_EQ(server.get_json("/jobs/" + high)["priority"], 6);
    EXPECT_EQ(server.get_json("/jobs/" + low)["priority"], 1);
    // The blocker was running before the kill, but the queue goes by priority: the highest first.
    json running;
    for (int i = 0; i < 1000 && running.is_null(); ++i) {
        for (const auto& id : {blocker, low, high})
            if (server.get_json("/jobs/" + id)["state"] == "running") running = id;
        std::this_thread::sleep_for(10ms);
    }
    EXPECT_EQ(running, high);
    EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace glint
