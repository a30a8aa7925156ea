#include "service/slurm_farm.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <spdlog/spdlog.h>

#include "base/files.h"

extern char** environ;

namespace glint {
namespace {

// Runs argv without a shell; returns its exit status (-1 if it could not start), with what it
// wrote to stdout and stderr in `output`.
int run_command(const std::vector<std::string>& argv, std::string& output) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) return -1;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
    // The server blocks its stop signals in every thread; the child must not inherit that.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid;
    const int spawned = posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    close(fds[1]);
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) output.append(buffer, size_t(n));
    close(fds[0]);
    if (spawned != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_text(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::filesystem::path part_file(const FarmRun& run, size_t i, const char* extension) {
    return run.work / ("part-" + std::to_string(i) + extension);
}

}  // namespace

nlohmann::json FarmRun::to_json() const {
    return {{"array", array}, {"merge", merge}, {"work", work.string()}, {"ranges", ranges}};
}

FarmRun FarmRun::from_json(const nlohmann::json& j) {
    try {
        return {j.at("array").get<std::string>(), j.at("merge").get<std::string>(), j.at("work").get<std::string>(),
                j.at("ranges").get<std::vector<std::string>>()};
    } catch (const nlohmann::json::exception& e) {
        throw FarmError(std::string("not a farm run: ") + e.what());
    }
}

SlurmFarm::SlurmFarm(FarmConfig config, std::filesystem::path scenes)
    : config_(std::move(config)), scenes_(std::filesystem::absolute(std::move(scenes))) {}

std::vector<std::string> SlurmFarm::part_command(const std::filesystem::path& folder, const std::string& request,
                                                 const RenderSettings& settings) const {
    // A preset renders the scenes folder's file; any other request is the scene itself, whose
    // meshes the part reads from the scenes folder, as the server does. Either way the film
    // options given make the job's own settings, so the parts' fingerprint is the job's.
    std::filesystem::path scene;
    std::vector<std::string> options;
    nlohmann::json parsed = nlohmann::json::parse(request, nullptr, false);
    if (parsed.is_object() && parsed.contains("preset") && parsed.at("preset").is_string()) {
        scene = scenes_ / (parsed.at("preset").get<std::string>() + ".json");
    } else {
        scene = folder / "scene.json";
        parsed.erase("priority");  // the job's, not the scene's: glint render refuses it
        const std::string text = parsed.dump();
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

FarmRun SlurmFarm::submit(const std::string& job_id, const std::string& request, const RenderSettings& settings) const {
    const std::filesystem::path folder = std::filesystem::absolute(config_.dir / job_id);
    std::filesystem::create_directories(folder);
    std::vector<std::string> part = part_command(folder, request, settings);
    std::vector<std::string> argv = {(config_.scripts / "submit").string(), part.front(), "-o", (folder / "image.png").string(),
                                     "--parts", std::to_string(config_.parts), "--spp", std::to_string(settings.spp),
                                     "--work", (folder / "parts").string(), "--glint", config_.glint};
    if (!config_.sbatch.empty()) argv.insert(argv.end(), {"--sbatch", config_.sbatch});
    argv.push_back("--");
    argv.insert(argv.end(), part.begin() + 1, part.end());
    std::string output;
    if (run_command(argv, output) != 0) throw FarmError("Slurm did not take the job: " + output);
    std::smatch parts, merge;
    if (!std::regex_search(output, parts, std::regex(R"(parts: job (\d+) \(tasks \S+, samples ([^)]*)\))")) ||
        !std::regex_search(output, merge, std::regex(R"(merge: job (\d+))")))
        throw FarmError("unexpected answer from docker/slurm/submit: " + output);
    FarmRun result{parts[1], merge[1], folder / "parts", {}};
    std::istringstream ranges(parts[2]);
    for (std::string r; ranges >> r;) result.ranges.push_back(r);
    return result;
}

PartCounts SlurmFarm::count(const FarmRun& run) const {
    PartCounts counts;
    for (size_t i = 0; i < run.ranges.size(); ++i) {
        if (std::filesystem::exists(part_file(run, i, ".partial"))) ++counts.done;
        if (read_text(part_file(run, i, ".log")).find(", attempt 2,") != std::string::npos) ++counts.requeued;
    }
    std::string output;
    if (run_command({"squeue", "-h", "-r", "-j", run.array, "-o", "%t"}, output) != 0) return counts;
    std::istringstream states(output);
    for (std::string state; states >> state;) {
        if (state == "PD") ++counts.queued;
        else if (state == "R" || state == "CG") ++counts.running;
    }
    return counts;
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

bool SlurmFarm::refresh(const FarmRun& run, size_t i, PartFilm& part) const {
    if (part.done) return false;
    std::error_code error;
    const std::filesystem::path final_file = part_file(run, i, ".partial");
    const bool done = std::filesystem::exists(final_file, error);
    const std::filesystem::path file = done ? final_file : part_file(run, i, ".checkpoint");
    const auto time = std::filesystem::last_write_time(file, error);
    if (error || (!done && time == part.read_at)) return false;
    Partial film = decode_partial(read_file(file.string(), size_t(8) << 30));
    // A requeued part continues from its checkpoint, so a newer file never holds fewer samples;
    // keeping the larger one anyway means a part's samples are never counted twice or lost.
    if (part.film && film.end_sample < part.film->end_sample && !done) return false;
    part = {std::move(film), done, time};
    return true;
}

std::optional<std::string> SlurmFarm::failure(const FarmRun& run) const {
    for (size_t i = 0; i < run.ranges.size(); ++i)
        if (std::filesystem::exists(part_file(run, i, ".failed"))) return read_text(part_file(run, i, ".failed"));
    return std::nullopt;
}

}  // namespace glint
