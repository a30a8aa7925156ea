#include "service/slurm_farm.h"

#include <sstream>

#include <spdlog/spdlog.h>

#include "base/files.h"
#include "service/subprocess.h"

namespace glint {
namespace {

constexpr size_t kMaxReportBytes = size_t(1) << 20, kMaxPartFilmBytes = size_t(8) << 30;

std::filesystem::path part_file(const FarmRun& run, size_t i, const char* extension) {
    return run.work / ("part-" + std::to_string(i) + extension);
}

// Reads `file` again if it changed since `read_at` (which then moves on); false if it did not
// change or is not there.
bool changed_since(const std::filesystem::path& file, std::filesystem::file_time_type& read_at) {
    std::error_code error;
    const auto time = std::filesystem::last_write_time(file, error);
    if (error || time == read_at) return false;
    read_at = time;
    return true;
}

// Rereads part i's film if its file changed: its partial file once done, else its checkpoint.
bool refresh_film(const FarmRun& run, size_t i, PartState& part) {
    if (part.done) return false;
    std::error_code error;
    const std::filesystem::path final_file = part_file(run, i, ".partial");
    const bool done = std::filesystem::exists(final_file, error);
    const std::filesystem::path file = done ? final_file : part_file(run, i, ".checkpoint");
    const auto time = std::filesystem::last_write_time(file, error);
    if (error || (!done && time == part.film_read_at)) return false;
    Partial film = decode_partial(read_file(file.string(), kMaxPartFilmBytes));
    part.film_read_at = time;
    // A requeued part continues from its checkpoint, so a newer file never holds fewer samples;
    // keeping the larger one anyway means a part's samples are never counted twice or lost.
    if (part.film && film.end_sample < part.film->end_sample && !done) return false;
    part.film = std::move(film);
    part.done = done;
    return true;
}

// The attempt docker/slurm/render-part wrote into part-i.attempt, reread only if it changed.
void refresh_attempt(const FarmRun& run, size_t i, PartState& part) {
    if (!changed_since(part_file(run, i, ".attempt"), part.attempt_read_at)) return;
    try {
        part.attempt = std::stoi(read_text(part_file(run, i, ".attempt"), 64));
    } catch (const std::exception&) {  // written atomically, so only a foreign file is unreadable
    }
}

}  // namespace

SlurmFarm::SlurmFarm(FarmConfig config, std::filesystem::path scenes)
    : config_(std::move(config)), scenes_(std::filesystem::absolute(std::move(scenes))) {}

std::vector<std::string> SlurmFarm::part_command(const std::filesystem::path& folder, const SceneSource& source,
                                                 const RenderSettings& settings) const {
    // A preset renders the scenes folder's file; any other scene is written for the parts, which
    // read its meshes from the scenes folder, as the server does. Either way the film options
    // given make the job's own settings, so the parts' fingerprint is the job's.
    std::filesystem::path scene;
    std::vector<std::string> options;
    if (!source.preset.empty()) {
        scene = scenes_ / (source.preset + ".json");
    } else {
        scene = folder / "scene.json";
        const std::string text = source.scene.dump();
        write_file(scene.string(), std::vector<uint8_t>(text.begin(), text.end()));
        options = {"--scenes", scenes_.string()};
    }
    if (!settings.whole_image()) {
        const Region& r = settings.region;
        options.insert(options.end(), {"--region", std::to_string(r.x0) + "," + std::to_string(r.y0) + "," +
                                                       std::to_string(r.x1) + "," + std::to_string(r.y1)});
    }
    const std::vector<std::string> film = {
        "--width", std::to_string(settings.width), "--height", std::to_string(settings.height),
        "--seed", std::to_string(settings.seed), "--encoding", settings.encoding == Encoding::srgb ? "srgb" : "gamma2.2",
        "--checkpoint-interval", std::to_string(config_.checkpoint_interval)};
    options.insert(options.end(), film.begin(), film.end());
    if (settings.aovs) options.push_back("--aovs");
    options.insert(options.begin(), scene.string());
    return options;
}

// docker/slurm/submit writes its submission to --report as one JSON object.
FarmRun SlurmFarm::submit(const std::string& job_id, const SceneSource& source, const RenderSettings& settings) const {
    const std::filesystem::path folder = std::filesystem::absolute(config_.dir / job_id);
    std::filesystem::create_directories(folder);
    const std::filesystem::path report = folder / "submitted.json";
    std::filesystem::remove(report);
    std::vector<std::string> part = part_command(folder, source, settings);
    std::vector<std::string> argv = {(config_.scripts / "submit").string(), part.front(), "-o", (folder / "image.png").string(),
                                     "--parts", std::to_string(config_.parts), "--spp", std::to_string(settings.spp),
                                     "--work", (folder / "parts").string(), "--glint", config_.glint,
                                     "--report", report.string()};
    if (!config_.sbatch.empty()) argv.insert(argv.end(), {"--sbatch", config_.sbatch});
    argv.push_back("--");
    argv.insert(argv.end(), part.begin() + 1, part.end());
    std::string output;
    if (run_command(argv, output) != 0) throw FarmError("Slurm did not take the job: " + output);
    try {
        const nlohmann::json submitted = nlohmann::json::parse(read_text(report, kMaxReportBytes));
        return {submitted.at("array").get<std::string>(), submitted.at("merge").get<std::string>(), folder / "parts",
                submitted.at("ranges").get<std::vector<std::string>>()};
    } catch (const std::exception& e) {
        throw FarmError("docker/slurm/submit gave no submission in " + report.string() + ": " + e.what() + "; it said: " +
                        output);
    }
}

FarmRun SlurmFarm::resume(const nlohmann::json& saved) const { return FarmRun::from_json(saved); }

FarmPoll SlurmFarm::poll(const FarmRun& run, std::vector<PartState>& parts) const {
    FarmPoll result;
    for (size_t i = 0; i < parts.size(); ++i) {
        std::error_code error;
        if (std::filesystem::exists(part_file(run, i, ".failed"), error)) {
            result.failure = read_text(part_file(run, i, ".failed"), kMaxReportBytes);
            return result;
        }
    }
    for (size_t i = 0; i < parts.size(); ++i) {
        PartState& part = parts[i];
        result.films_changed |= refresh_film(run, i, part);
        refresh_attempt(run, i, part);
        result.counts.done += part.done;
        result.counts.requeued += part.attempt >= 2;
    }
    count_queue(run, result.counts);
    return result;
}

void SlurmFarm::count_queue(const FarmRun& run, PartCounts& counts) const {
    std::string output;
    if (run_command({"squeue", "-h", "-r", "-j", run.array, "-o", "%t"}, output) != 0) return;
    std::istringstream states(output);
    for (std::string state; states >> state;) {
        if (state == "PD") ++counts.queued;
        else if (state == "R" || state == "CG") ++counts.running;
    }
}

// A busy controller can time scancel out (MessageTimeout), and parts it failed to cancel would
// hold the cluster's nodes for all their remaining samples: a failure is retried, then logged.
void SlurmFarm::cancel(const FarmRun& run) const {
    std::string output;
    for (int attempt = 0; attempt < 3; ++attempt) {
        output.clear();
        if (run_command({"scancel", run.array, run.merge}, output) == 0) return;
    }
    spdlog::warn("scancel {} {} failed: {}", run.array, run.merge, output);
}

}  // namespace glint
