#include "job_store.h"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "base/files.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr size_t kMaxRequestBytes = size_t(64) << 20, kMaxStateBytes = size_t(1) << 20;

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

std::string read_text(const fs::path& file, size_t max_bytes) {
    const std::vector<uint8_t> bytes = read_file(file.string(), max_bytes);
    return {bytes.begin(), bytes.end()};
}

json progress_to_json(const Progress& p) {
    return {{"spp_done", p.spp_done},
            {"spp_target", p.spp_target},
            {"seconds", p.seconds},
            {"samples_per_second", p.samples_per_second},
            {"error_estimate", std::isfinite(p.error_estimate) ? json(p.error_estimate) : json()},
            {"dropped", p.dropped}};
}

Progress progress_from_json(const json& j) {
    Progress p;
    p.spp_done = j.at("spp_done").get<uint32_t>();
    p.spp_target = j.at("spp_target").get<uint32_t>();
    p.seconds = j.at("seconds").get<double>();
    p.samples_per_second = j.at("samples_per_second").get<double>();
    p.error_estimate = j.at("error_estimate").is_null() ? kInfinity : j.at("error_estimate").get<double>();
    p.dropped = j.at("dropped").get<uint64_t>();
    return p;
}

JobState state_from_string(const std::string& name) {
    for (JobState s : {JobState::queued, JobState::running, JobState::done, JobState::cancelled, JobState::failed})
        if (name == to_string(s)) return s;
    throw std::invalid_argument("unknown state \"" + name + "\"");
}

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
            job.created = std::chrono::system_clock::time_point(
                std::chrono::system_clock::duration(state.at("created").get<int64_t>()));
            job.state = state_from_string(state.at("state").get<std::string>());
            job.error = state.at("error").get<std::string>();
            job.progress = progress_from_json(state.at("progress"));
            jobs.push_back(std::move(job));
        } catch (const std::exception& e) {
            spdlog::error("store: job {} left out: cannot read its request or state in {}: {}", id,
                          entry.path().string(), e.what());
        }
    }
    std::sort(jobs.begin(), jobs.end(), [](const StoredJob& a, const StoredJob& b) {
        return a.created != b.created ? a.created < b.created : a.id < b.id;
    });
    return jobs;
}

void JobStore::save_request(const std::string& id, const std::string& request) const {
    fs::create_directories(folder(id));
    write_file((folder(id) / "request.json").string(), bytes_of(request));
}

void JobStore::save_state(const std::string& id, std::chrono::system_clock::time_point created, JobState state,
                          const std::string& error, const Progress& progress) const {
    const json j = {{"created", int64_t(created.time_since_epoch().count())},
                    {"state", to_string(state)},
                    {"error", error},
                    {"progress", progress_to_json(progress)}};
    write_file((folder(id) / "state.json").string(), bytes_of(j.dump()));
}

fs::path JobStore::film_path(const std::string& id, FilmFile which) const {
    return folder(id) / (which == FilmFile::checkpoint ? "checkpoint.glntpart" : "final.glntpart");
}

void JobStore::save_film(const std::string& id, FilmFile which, const Partial& film) const {
    write_file(film_path(id, which).string(), encode_partial(film));
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
