#include "service/job_store.h"

#include <algorithm>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "base/files.h"
#include "service/progress_json.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr size_t kMaxRequestBytes = size_t(64) << 20, kMaxStateBytes = size_t(1) << 20;

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

bool is_job_id(const std::string& name) {
    return name.size() == 16 && std::all_of(name.begin(), name.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// A crash in the middle of write_file leaves its temporary file behind.
void remove_temporaries(const fs::path& folder) {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error))
        if (entry.path().extension() == ".tmp") fs::remove(entry.path(), error);
}

uint64_t folder_bytes(const fs::path& folder) {
    uint64_t total = 0;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error)) {
        // A running job may replace or remove a file meanwhile: count what is still there.
        std::error_code gone;
        const uintmax_t size = entry.is_regular_file(gone) ? entry.file_size(gone) : 0;
        if (!gone) total += size;
    }
    return total;
}

JobRecord record_from_json(const json& state) {
    JobRecord r;
    r.created = std::chrono::system_clock::time_point(std::chrono::system_clock::duration(state.at("created").get<int64_t>()));
    r.state = job_state_named(state.at("state").get<std::string>());
    r.error = state.at("error").get<std::string>();
    r.progress = progress_from_json(state.at("progress"));
    r.priority = state.value("priority", 0);
    if (state.contains("stop_reason")) r.stop = stop_reason_named(state.at("stop_reason").get<std::string>());
    return r;
}

}  // namespace

JobStore::JobStore(StoreConfig config) : config_(std::move(config)) {
    std::error_code error;
    fs::create_directories(config_.dir, error);
    if (error || !fs::is_directory(config_.dir))
        throw FileError("cannot create the store folder " + config_.dir.string() + ": " + error.message());
}

std::vector<StoredJob> JobStore::load() const {
    std::vector<StoredJob> jobs;
    for (const auto& entry : fs::directory_iterator(config_.dir)) {
        const std::string id = entry.path().filename().string();
        if (!entry.is_directory() || !is_job_id(id)) continue;
        remove_temporaries(entry.path());
        try {
            const json state = json::parse(read_text(entry.path() / "state.json", kMaxStateBytes));
            StoredJob job;
            job.id = id;
            job.request = read_text(entry.path() / "request.json", kMaxRequestBytes);
            job.record = record_from_json(state);
            if (fs::exists(entry.path() / "farm.json")) job.farm = read_text(entry.path() / "farm.json", kMaxStateBytes);
            jobs.push_back(std::move(job));
        } catch (const std::exception& e) {
            spdlog::error("store: job {} left out: cannot read its request or state in {}: {}", id,
                          entry.path().string(), e.what());
        }
    }
    std::sort(jobs.begin(), jobs.end(), [](const StoredJob& a, const StoredJob& b) {
        return a.record.created != b.record.created ? a.record.created < b.record.created : a.id < b.id;
    });
    return jobs;
}

void JobStore::save_request(const std::string& id, const std::string& request) const {
    fs::create_directories(folder(id));
    write_file((folder(id) / "request.json").string(), bytes_of(request));
}

void JobStore::save_state(const std::string& id, const JobRecord& r) const {
    json j = {{"created", int64_t(r.created.time_since_epoch().count())},
              {"state", to_string(r.state)},
              {"error", r.error},
              {"progress", progress_json(r.progress)},
              {"priority", r.priority}};
    if (r.stop) j["stop_reason"] = stop_reason_name(*r.stop);
    write_file((folder(id) / "state.json").string(), bytes_of(j.dump()));
}

fs::path JobStore::film_path(const std::string& id, FilmFile which) const {
    return folder(id) / (which == FilmFile::checkpoint ? "checkpoint.glntpart" : "final.glntpart");
}

void JobStore::save_film(const std::string& id, FilmFile which, const Partial& film) const {
    write_file(film_path(id, which).string(), encode_partial(film));
}

void JobStore::save_farm(const std::string& id, const std::string& farm) const {
    write_file((folder(id) / "farm.json").string(), bytes_of(farm));
}

Partial JobStore::load_film(const std::string& id, FilmFile which) const {
    return decode_partial(read_file(film_path(id, which).string(), SIZE_MAX));
}

bool JobStore::has_film(const std::string& id, FilmFile which) const {
    std::error_code error;
    return fs::exists(film_path(id, which), error);
}

void JobStore::remove(const std::string& id) const {
    std::error_code error;
    fs::remove_all(folder(id), error);
    if (error) spdlog::error("store: cannot remove {}: {}", folder(id).string(), error.message());
}

uint64_t JobStore::job_bytes(const std::string& id) const { return folder_bytes(folder(id)); }

uint64_t JobStore::bytes_used() const {
    uint64_t total = 0;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(config_.dir, error))
        if (entry.is_directory(error)) total += folder_bytes(entry.path());
    return total;
}

}  // namespace glint
