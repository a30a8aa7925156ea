// The server against clients that misbehave: paths that try to leave the web folder, missing
// or wrong tokens, too many streams from one address, requests sent one byte at a time. Real
// servers on 127.0.0.1 and free ports; raw sockets where an HTTP library would tidy the request.
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "http/auth.h"
#include "http/render_server.h"
#include "support/raw_http.h"

namespace glint {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::RawConnection;
using testing::body_of;
using testing::status_of;

constexpr auto kPatience = 30s;  // generous bound for any answer the test waits for

// A server's configuration for these tests: presets from scenes/, one render thread, a free port.
struct Config {
    ServiceConfig service;
    HttpConfig http;
};

Config config_with(const std::filesystem::path& web = GLINT_WEB_DIR) {
    Config config;
    config.service.scenes = GLINT_SCENES_DIR;
    config.service.threads = 1;
    config.http.web = web;
    config.http.port = 0;
    return config;
}

std::unique_ptr<RenderServer> start(const Config& config) {
    return std::make_unique<RenderServer>(config.service, config.http);
}

// One raw request on its own connection; the whole response.
std::string raw(int port, const std::string& request_line, const std::string& headers = "") {
    RawConnection c(port);
    c.send(request_line + "\r\nHost: 127.0.0.1\r\nConnection: close\r\n" + headers + "\r\n");
    return c.read_until_closed(kPatience);
}

class WebFolder : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = std::filesystem::temp_directory_path() / ("glint-web-test-" + std::to_string(::getpid()));
        std::filesystem::create_directories(root_ / "web" / "sub");
        std::filesystem::create_directories(root_ / "private");
        write(root_ / "web" / "index.html", "<title>inside</title>");
        write(root_ / "web" / "sub" / "page.txt", "sub page");
        write(root_ / "secret.txt", "SECRET-OUTSIDE");
        write(root_ / "private" / "key.txt", "SECRET-DIR");
        std::filesystem::create_symlink(root_ / "secret.txt", root_ / "web" / "link.txt");
        std::filesystem::create_symlink(root_ / "private", root_ / "web" / "dirlink");
        std::filesystem::create_symlink(root_ / "web" / "sub" / "page.txt", root_ / "web" / "inner.txt");
        service_ = start(config_with(root_ / "web"));
    }
    void TearDown() override {
        service_.reset();
        std::filesystem::remove_all(root_);
    }
    static void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

    std::filesystem::path root_;
    std::unique_ptr<RenderServer> service_;
};

TEST_F(WebFolder, ServesFilesInsideTheFolder) {
    const int port = service_->port();
    EXPECT_NE(raw(port, "GET / HTTP/1.1").find("<title>inside</title>"), std::string::npos);
    EXPECT_NE(raw(port, "GET /sub/page.txt HTTP/1.1").find("sub page"), std::string::npos);
    EXPECT_NE(raw(port, "GET /sub/../index.html HTTP/1.1").find("inside"), std::string::npos);
    EXPECT_NE(raw(port, "GET /inner.txt HTTP/1.1").find("sub page"), std::string::npos);  // a symlink within
    EXPECT_EQ(status_of(raw(port, "GET /missing.html HTTP/1.1")), 404);
}

TEST_F(WebFolder, RefusesEveryWayOut) {
    const int port = service_->port();
    for (const std::string target : {"/../secret.txt", "/sub/../../secret.txt", "/%2e%2e/secret.txt",
                                     "/%2E%2E/secret.txt", "/..%2fsecret.txt", "/%2e%2e%2fsecret.txt",
                                     "/sub%2f..%2f..%2fsecret.txt", "//etc/passwd", "/%2fetc%2fpasswd",
                                     "/link.txt", "/dirlink/key.txt", "/index.html%00.txt"}) {
        const std::string response = raw(port, "GET " + target + " HTTP/1.1");
        EXPECT_EQ(status_of(response), 403) << target << "\n" << response;
        EXPECT_EQ(response.find("SECRET"), std::string::npos) << target;
        EXPECT_EQ(response.find("root:"), std::string::npos) << target;
        EXPECT_EQ(json::parse(body_of(response))["error"], "path leaves the web folder") << target;
    }
}

// Found by fuzzing (tests/fuzz/regressions/job_request/): the request parser let nlohmann's
// out_of_range for 1e999 escape, which the server answered with a 500.
TEST(FuzzFindings, ANumberBeyondDoubleIsAMalformedRequest) {
    RenderServer service(config_with().service, config_with().http);
    httplib::Client client("127.0.0.1", service.port());
    auto res = client.Post("/jobs", R"({"preset": "cornell", "spp": 1e999})", "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    EXPECT_EQ(json::parse(res->body)["error"], "malformed JSON at byte 34: number overflow parsing '1e999'");
}

// Found in review: the request parser read a preset request's JSON without the scene parser's
// depth bound, so 16 MiB of '[' built 16 M nested arrays (about 1 GB) before any check.
TEST(Limits, DeepNestingInAPresetRequestIsRefusedWhileParsing) {
    RenderServer service(config_with().service, config_with().http);
    httplib::Client client("127.0.0.1", service.port());
    const std::string deep = R"({"preset": "cornell", "x": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
    auto res = client.Post("/jobs", deep, "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    EXPECT_EQ(json::parse(res->body)["error"], "JSON nested deeper than 32 levels");
}

class WithToken : public ::testing::Test {
protected:
    void SetUp() override {
        Config config = config_with();
        config.http.token = kToken;
        config.service.threads = 2;
        service_ = start(config);
        client_ = std::make_unique<httplib::Client>("127.0.0.1", service_->port());
        client_->set_read_timeout(60, 0);
    }
    static constexpr const char* kToken = "correct-horse-battery-staple";
    std::unique_ptr<RenderServer> service_;
    std::unique_ptr<httplib::Client> client_;
};

const std::string kSmallJob = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 4})";

TEST_F(WithToken, JobRoutesNeedTheToken) {
    const httplib::Headers none, wrong{{"Authorization", "Bearer correct-horse"}}, right{{"Authorization", std::string("Bearer ") + kToken}};
    auto refused = [](const httplib::Result& res, const std::string& error) {
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 401);
        EXPECT_EQ(res->get_header_value("WWW-Authenticate"), "Bearer");
        EXPECT_EQ(json::parse(res->body)["error"], error);
    };
    const std::string missing = "this server needs a bearer token (header Authorization: Bearer TOKEN)";
    refused(client_->Post("/jobs", none, kSmallJob, "application/json"), missing);
    refused(client_->Post("/render", none, kSmallJob, "application/json"), missing);
    refused(client_->Post("/jobs", wrong, kSmallJob, "application/json"), "wrong bearer token");
    refused(client_->Get("/jobs", none), missing);
    refused(client_->Get("/jobs", {{"Authorization", "Basic Zm9vOmJhcg=="}}), "the Authorization header must be \"Bearer TOKEN\"");
    refused(client_->Get((std::string("/jobs?token=") + kToken).c_str()),
            "the token may be a query parameter only on stream, events and image routes");

    auto accepted = client_->Post("/jobs", right, kSmallJob, "application/json");
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 202) << accepted->body;
    const std::string id = json::parse(accepted->body)["id"];
    refused(client_->Get(("/jobs/" + id).c_str(), none), missing);
    refused(client_->Delete(("/jobs/" + id).c_str(), wrong), "wrong bearer token");
    refused(client_->Get(("/jobs/" + id + "/events").c_str()), missing);
    refused(client_->Get(("/jobs/" + id + "/image.png?token=nope").c_str()), "wrong bearer token");
    EXPECT_EQ(client_->Get(("/jobs/" + id).c_str(), right)->status, 200);
    // Streams and images, which <img> and EventSource load without headers, take it in the query.
    auto events = client_->Get(("/jobs/" + id + "/events?token=" + kToken).c_str());
    ASSERT_TRUE(events);
    EXPECT_EQ(events->status, 200);
    EXPECT_NE(events->body.find("event: done"), std::string::npos);
    EXPECT_EQ(client_->Get(("/jobs/" + id + "/image.png?token=" + kToken).c_str())->status, 200);
    // The page, the presets and the health check stay open.
    EXPECT_EQ(client_->Get("/")->status, 200);
    EXPECT_EQ(client_->Get("/presets")->status, 200);
    EXPECT_EQ(client_->Get("/health")->status, 200);
}

TEST_F(WithToken, ARefusedUploadDoesNotDisturbTheNextRequest) {
    // The refused body is never read; the connection is closed rather than parsed as a request.
    RawConnection c(service_->port());
    c.send("POST /jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: " +
           std::to_string(kSmallJob.size()) + "\r\n\r\n" + kSmallJob);
    const std::string response = c.read_until_closed(kPatience);
    EXPECT_EQ(status_of(response), 401);
    EXPECT_TRUE(c.closed());
    EXPECT_EQ(response.find("HTTP/1.1 400"), std::string::npos);
}

TEST(Token, RefusesToListenBeyondLoopbackWithoutOne) {
    try {
        Config config = config_with();
        config.http.host = "0.0.0.0";
        RenderServer service(config.service, config.http);
        FAIL() << "started on 0.0.0.0 without a token";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "refusing to listen on 0.0.0.0 without a token: anyone who reaches it could run jobs; set --token or GLINT_TOKEN");
    }
}

TEST(Token, LoopbackAddressesAndConstantTimeComparison) {
    for (const char* host : {"127.0.0.1", "127.1.2.3", "::1", "localhost", "::ffff:127.0.0.1"})
        EXPECT_TRUE(is_loopback_host(host)) << host;
    for (const char* host : {"0.0.0.0", "::", "192.168.1.10", "10.0.0.1", "::ffff:10.0.0.1", "example.com", "", "128.0.0.1"})
        EXPECT_FALSE(is_loopback_host(host)) << host;
    EXPECT_TRUE(same_secret("abc", "abc"));
    EXPECT_FALSE(same_secret("abd", "abc"));
    EXPECT_FALSE(same_secret("ab", "abc"));
    EXPECT_FALSE(same_secret("abcd", "abc"));
    EXPECT_FALSE(same_secret("", "abc"));
    EXPECT_FALSE(same_secret(std::string("ab\0", 3), "ab"));
}

TEST(Limits, StreamsPerClientGet429) {
    Config config = config_with();
    config.http.streams_per_client = 2;
    RenderServer service(config.service, config.http);
    httplib::Client client("127.0.0.1", service.port());
    auto accepted = client.Post("/jobs", R"({"preset": "cornell", "width": 32, "height": 24, "spp": 65536})", "application/json");
    ASSERT_TRUE(accepted);
    const std::string id = json::parse(accepted->body)["id"];
    const std::string events = "GET /jobs/" + id + "/events HTTP/1.1\r\nHost: x\r\n\r\n";
    auto first = std::make_unique<RawConnection>(service.port());
    RawConnection second(service.port());
    first->send(events);
    second.send(events);
    EXPECT_EQ(status_of(first->read_headers(kPatience)), 200);
    EXPECT_EQ(status_of(second.read_headers(kPatience)), 200);
    const std::string third = raw(service.port(), "GET /jobs/" + id + "/stream HTTP/1.1");
    EXPECT_EQ(status_of(third), 429);
    EXPECT_EQ(json::parse(body_of(third))["error"], "too many open streams from 127.0.0.1 (limit 2 per client)");
    // Other requests from the same client are unaffected; a closed stream frees its place.
    EXPECT_EQ(client.Get(("/jobs/" + id).c_str())->status, 200);
    first.reset();
    int status = 0;
    for (int i = 0; i < 100 && status != 200; ++i) {
        RawConnection again(service.port());
        again.send("GET /jobs/" + id + "/stream HTTP/1.1\r\nHost: x\r\n\r\n");
        status = status_of(again.read_headers(kPatience));
        if (status != 200) std::this_thread::sleep_for(100ms);
    }
    EXPECT_EQ(status, 200);
    client.Delete(("/jobs/" + id).c_str());
}

// Sends `start` at once, then `slow` one byte every 100 ms until the server answers or closes;
// returns what it answered and how many slow bytes had been sent by then.
struct Trickled {
    std::string response;
    size_t bytes_sent = 0;
};
Trickled trickle(int port, const std::string& start, const std::string& slow) {
    RawConnection c(port);
    Trickled t;
    c.send(start);
    while (t.bytes_sent < slow.size() && !c.answered() && c.send(slow.substr(t.bytes_sent, 1))) {
        ++t.bytes_sent;
        std::this_thread::sleep_for(100ms);
    }
    t.response = c.read_until_closed(kPatience);
    return t;
}

TEST(Limits, ASlowClientIsCutOffAndOthersAreServed) {
    Config config = config_with();
    config.http.threads = 2;  // two slow clients would hold every HTTP thread
    config.http.request_timeout = 1s;
    RenderServer service(config.service, config.http);
    // A minute's worth of bytes at this pace: without the deadline both threads stay busy.
    const std::string slow_headers = "GET /health HTTP/1.1\r\nHost: x\r\nX-Padding: " + std::string(600, 'p') + "\r\n\r\n";
    const std::string body_headers = "POST /jobs HTTP/1.1\r\nHost: x\r\nContent-Length: 600\r\n\r\n";
    Trickled headers_result, body_result;
    std::thread a([&] { headers_result = trickle(service.port(), "", slow_headers); });
    std::thread b([&] { body_result = trickle(service.port(), body_headers, std::string(600, ' ')); });
    std::this_thread::sleep_for(300ms);
    httplib::Client client("127.0.0.1", service.port());
    client.set_read_timeout(20, 0);  // far less than the slow clients would take
    auto health = client.Get("/health");
    a.join();
    b.join();
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
    for (const Trickled* t : {&headers_result, &body_result}) {
        EXPECT_EQ(status_of(t->response), 408) << t->response;
        EXPECT_NE(t->response.find("Connection: close"), std::string::npos);
        EXPECT_EQ(body_of(t->response), R"({"error":"request not received within 1000 ms"})");
        EXPECT_LT(t->bytes_sent, 400u);  // cut off long before it was done
    }
}

}  // namespace
}  // namespace glint
