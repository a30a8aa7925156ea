// A real `glint serve` in the test process, on 127.0.0.1 and a free port, and a cpp-httplib
// client for it: the fixture of the HTTP API's tests.
#pragma once

#include <gtest/gtest.h>

#include <stb_image.h>

#include <memory>
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "http/render_server.h"

namespace glint::testing {

using nlohmann::json;
using namespace std::chrono_literals;

class Server : public ::testing::Test {
protected:
    void start(ServiceConfig service = {}, HttpConfig http = {}) {
        service.scenes = GLINT_SCENES_DIR;
        service.threads = 2;
        http.web = GLINT_WEB_DIR;
        http.port = 0;
        service_ = std::make_unique<RenderServer>(service, http);
        client_ = std::make_unique<httplib::Client>("127.0.0.1", service_->port());
        client_->set_read_timeout(60, 0);
    }
    void SetUp() override { start(); }

    json patch(const std::string& path, const std::string& body, int expected_status) {
        auto res = client_->Patch(path.c_str(), body, "application/json");
        EXPECT_TRUE(res) << path;
        if (!res) return {};
        EXPECT_EQ(res->status, expected_status) << res->body;
        return json::parse(res->body);
    }
    json post(const std::string& path, const std::string& body, int expected_status) {
        auto res = client_->Post(path.c_str(), body, "application/json");
        EXPECT_TRUE(res) << path;
        if (!res) return {};
        EXPECT_EQ(res->status, expected_status) << res->body;
        return res->get_header_value("Content-Type") == "application/json" ? json::parse(res->body) : json{};
    }
    json get_json(const std::string& path, int expected_status = 200) {
        auto res = client_->Get(path.c_str());
        EXPECT_TRUE(res) << path;
        if (!res) return {};
        EXPECT_EQ(res->status, expected_status) << res->body;
        EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
        return json::parse(res->body);
    }
    json wait_until_final(const std::string& id) {
        for (int i = 0; i < 600; ++i) {
            const json s = get_json("/jobs/" + id);
            if (s["state"] != "queued" && s["state"] != "running") return s;
            std::this_thread::sleep_for(50ms);
        }
        ADD_FAILURE() << "job " << id << " did not finish";
        return {};
    }

    std::unique_ptr<RenderServer> service_;
    std::unique_ptr<httplib::Client> client_;
};

inline const std::string kSmallCornell = R"({"preset": "cornell", "width": 40, "height": 30, "spp": 16})";

struct Decoded {
    int width = 0, height = 0;
};
inline Decoded decode_png(const std::string& bytes) {
    Decoded d;
    int channels;
    unsigned char* pixels =
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &d.width, &d.height, &channels, 3);
    if (!pixels) return {};
    stbi_image_free(pixels);
    return d;
}

}  // namespace glint::testing
