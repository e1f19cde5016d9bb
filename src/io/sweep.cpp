// SPDX-License-Identifier: MIT
#include "io/sweep.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "io/csv_table.hpp"
#include "io/json.hpp"
#include "io/toml_reader.hpp"
#include "tumble/analysis/series.hpp"
#include "tumble/core/error.hpp"
#include "tumble/core/mpi.hpp"

extern char** environ;

namespace tumble::io {

namespace fs = std::filesystem;

// ============================================================ sweep file

namespace {

constexpr double g = 9.81;  // m/s^2, as tumble drum

std::vector<double> positive_numbers(const Reader& r, const toml::node& n, const std::string& key) {
    const auto* a = n.as_array();
    if (!a) r.fail(key, "expected an array of numbers, got " + type_name(n), &n);
    if (a->empty()) r.fail(key, "must not be empty", &n);
    std::vector<double> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
        const double v = r.number(*a->get(i), at(key, i), Bound::positive);
        if (std::find(out.begin(), out.end(), v) != out.end())
            r.fail(at(key, i), "the value " + show(v) + " is given twice", a->get(i));
        out.push_back(v);
    }
    return out;
}

}  // namespace

SweepSettings load_sweep_settings(const fs::path& file) {
    const toml::table root = parse_toml(read_text_file(file), file);
    const Reader r(file);
    SweepSettings s;
    r.only_keys(root, "", {"sweep", "output"});
    const toml::table& t = *r.table(root, "sweep", true);
    r.only_keys(t, "sweep",
                {"omega", "rpm", "froude", "modes", "seeds", "revolutions", "grains_two_component", "grains_self",
                 "samples_per_revolution", "snapshots_per_revolution", "diameter", "shear", "friction_normal",
                 "tangential_stiffness", "periodic_axis", "walls"});
    int given = 0;
    for (auto [key, unit] : {std::pair{"omega", SpeedUnit::rad_per_s}, std::pair{"rpm", SpeedUnit::rpm},
                             std::pair{"froude", SpeedUnit::froude}})
        if (const toml::node* n = t.get(key)) {
            s.speeds = positive_numbers(r, *n, join("sweep", key));
            s.speed_unit = unit;
            ++given;
        }
    if (given == 0) r.fail("sweep", "missing the speeds: give one of omega (rad/s), rpm or froude as a list", &t);
    if (given > 1) r.fail("sweep", "give the speeds once: omega (rad/s), rpm or froude, not several", &t);
    if (const toml::node* n = t.get("modes")) {
        const auto* a = n->as_array();
        if (!a) r.fail("sweep.modes", "expected an array of strings, got " + type_name(*n), n);
        if (a->empty()) r.fail("sweep.modes", "must not be empty", n);
        s.modes.clear();
        for (std::size_t i = 0; i < a->size(); ++i) {
            const std::string key = at("sweep.modes", i);
            std::string m = r.string(*a->get(i), key);
            if (m != "self" && m != "two-component")
                r.fail(key, "must be \"self\" or \"two-component\", got \"" + m + "\"", a->get(i));
            if (std::find(s.modes.begin(), s.modes.end(), m) != s.modes.end())
                r.fail(key, "the mode \"" + m + "\" is given twice", a->get(i));
            s.modes.push_back(std::move(m));
        }
    }
    if (const toml::node* n = t.get("seeds")) {
        const auto* a = n->as_array();
        if (!a) r.fail("sweep.seeds", "expected an array of integers, got " + type_name(*n), n);
        if (a->empty()) r.fail("sweep.seeds", "must not be empty", n);
        s.seeds.clear();
        for (std::size_t i = 0; i < a->size(); ++i) {
            const auto v = static_cast<std::uint64_t>(r.integer(*a->get(i), at("sweep.seeds", i), 0, INT64_MAX));
            if (std::find(s.seeds.begin(), s.seeds.end(), v) != s.seeds.end())
                r.fail(at("sweep.seeds", i), fmt::format("the seed {} is given twice", v), a->get(i));
            s.seeds.push_back(v);
        }
    }
    s.revolutions = r.number(t, "sweep", "revolutions", Bound::positive, s.revolutions);
    if (const toml::node* n = t.get("grains_two_component"))
        s.grains_two_component =
            static_cast<std::size_t>(r.integer(*n, "sweep.grains_two_component", 2, 10'000'000));
    if (const toml::node* n = t.get("grains_self"))
        s.grains_self = static_cast<std::size_t>(r.integer(*n, "sweep.grains_self", 2, 10'000'000));
    if (const toml::node* n = t.get("samples_per_revolution"))
        s.samples_per_revolution = static_cast<int>(r.integer(*n, "sweep.samples_per_revolution", 1, 100000));
    if (const toml::node* n = t.get("snapshots_per_revolution"))
        s.snapshots_per_revolution = static_cast<int>(r.integer(*n, "sweep.snapshots_per_revolution", 0, 100000));
    if (const toml::node* n = t.get("shear")) s.shear = r.keyword(*n, "sweep.shear", shear_models)->keyword;
    if (const toml::node* n = t.get("friction_normal"))
        s.friction_normal = r.keyword(*n, "sweep.friction_normal", friction_normals)->keyword;
    if (const toml::node* n = t.get("tangential_stiffness"))
        s.tangential_stiffness = r.keyword(*n, "sweep.tangential_stiffness", tangential_stiffnesses)->keyword;
    s.periodic_axis = r.boolean(t, "sweep", "periodic_axis", s.periodic_axis);
    if (const toml::node* n = t.get("walls")) s.walls = r.keyword(*n, "sweep.walls", drum_wall_kinds)->keyword;
    s.diameter = r.number(t, "sweep", "diameter", Bound::positive, s.diameter);
    if (t.get("diameter") && s.speed_unit != SpeedUnit::froude)
        r.fail("sweep.diameter", "only used to turn froude into omega; give it with froude only", t.get("diameter"));
    if (const toml::table* o = r.table(root, "output", false)) {
        r.only_keys(*o, "output", {"directory"});
        if (const toml::node* n = o->get("directory")) s.output = r.string(*n, "output.directory");
    }
    return s;
}

// ============================================================ points

std::string sweep_point_name(const std::string& mode, double omega, std::uint64_t seed) {
    return fmt::format("{}_omega{:.3f}_seed{}", mode, omega, seed);
}

std::vector<SweepPoint> expand_sweep(const SweepSettings& s, const fs::path& directory) {
    std::vector<SweepPoint> out;
    std::set<std::string> names;
    for (const std::string& mode : s.modes)
        for (double speed : s.speeds)
            for (std::uint64_t seed : s.seeds) {
                SweepPoint p;
                p.index = out.size();
                p.mode = mode;
                DrumSettings d;
                d.geometry.diameter = s.diameter;
                d.speed = speed;
                d.speed_unit = s.speed_unit;
                p.omega = d.omega();
                p.froude = p.omega * p.omega * 0.5 * s.diameter / g;
                p.seed = seed;
                p.revolutions = s.revolutions;
                p.grains = mode == "self" ? s.grains_self : s.grains_two_component;
                p.samples_per_revolution = s.samples_per_revolution;
                p.snapshots_per_revolution = s.snapshots_per_revolution;
                p.shear = s.shear;
                p.friction_normal = s.friction_normal;
                p.tangential_stiffness = s.tangential_stiffness;
                p.periodic_axis = s.periodic_axis;
                p.walls = s.walls;
                p.name = sweep_point_name(mode, p.omega, seed);
                p.directory = directory / "points" / p.name;
                if (!names.insert(p.name).second)
                    throw Error("sweep: two speeds give the same point directory " + p.name +
                                " (omega is named to 3 decimals); make the speeds differ more");
                out.push_back(std::move(p));
            }
    return out;
}

std::vector<std::string> drum_arguments(const SweepPoint& p) {
    std::vector<std::string> arguments{"drum",
            "-q",
            "--mode",
            p.mode,
            "--omega",
            fmt::format("{}", p.omega),  // shortest form that reads back exactly
            "--seed",
            std::to_string(p.seed),
            "--revolutions",
            fmt::format("{}", p.revolutions),
            "--grains",
            std::to_string(p.grains),
            "--samples",
            std::to_string(p.samples_per_revolution),
            "--snapshots",
            std::to_string(p.snapshots_per_revolution),
            "--shear",
            p.shear,
            "--friction-normal",
            p.friction_normal,
            "--tangential-stiffness",
            p.tangential_stiffness,
            "--out",
            p.directory.string(),
            "--force",
            "--threads",  // the sweep runs its points side by side, one core each
            "1"};
    if (p.periodic_axis) arguments.push_back("--periodic-axis");
    if (p.walls != "particles") arguments.insert(arguments.end(), {"--walls", p.walls});
    return arguments;
}

std::vector<std::string> resume_arguments(const SweepPoint& p) { return {"resume", "-q", p.directory.string()}; }

// ============================================================ state on disk

const char* to_string(PointState s) {
    switch (s) {
        case PointState::pending: return "pending";
        case PointState::unfinished: return "unfinished";
        case PointState::failed: return "failed";
        case PointState::finished: return "finished";
    }
    return "?";
}

PointState point_state(const fs::path& dir) {
    std::error_code ec;
    if (fs::exists(dir / point_summary_file, ec)) return PointState::finished;
    if (fs::exists(dir / point_failed_file, ec)) return PointState::failed;
    if (fs::is_directory(dir, ec)) return PointState::unfinished;
    return PointState::pending;
}

void write_failure_marker(const fs::path& dir, int exit_code) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    std::ofstream out(dir / point_failed_file, std::ios::trunc);
    out << "exit code " << exit_code << "\n";
    if (!out) throw Error((dir / point_failed_file).string() + ": cannot write the failure marker");
}

// ============================================================ child processes

int spawn_process(const std::vector<std::string>& argv, const fs::path& log) {
    if (argv.empty()) throw Error("spawn: empty command line");
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> environment;
    for (char** e = environ; *e; ++e) {
        const std::string_view entry(*e);
        if (!mpi::is_launcher_variable(entry.substr(0, entry.find('=')))) environment.push_back(*e);
    }
    environment.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environment.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw Error(fmt::format("cannot start {}: {}", argv[0], std::strerror(rc)));
    return pid;
}

int decode_wait_status(int status) {
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return 255;
}

fs::path self_executable() {
    std::error_code ec;
    fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error("cannot find the running executable (/proc/self/exe): " + ec.message());
    return p;
}

std::vector<PointOutcome> run_jobs(const NextJob& next, unsigned parallel,
                                   const std::function<void(const PointJob&)>& on_start,
                                   const std::function<void(const PointJob&, const PointOutcome&)>& on_finish,
                                   const std::function<bool()>& stop) {
    using Clock = std::chrono::steady_clock;
    struct Running {
        PointJob job;
        pid_t pid;
        Clock::time_point start;
    };
    parallel = std::max(1u, parallel);
    std::vector<PointOutcome> outcomes;
    std::vector<Running> running;
    auto finish = [&](const PointJob& job, int code, Clock::time_point start) {
        const PointOutcome o{job.point, code, std::chrono::duration<double>(Clock::now() - start).count()};
        outcomes.push_back(o);
        if (on_finish) on_finish(job, o);
    };
    bool exhausted = false, stopping = false;
    while ((!exhausted && !stopping) || !running.empty()) {
        if (!stopping && stop && stop()) {
            stopping = true;
            for (const Running& r : running) ::kill(r.pid, SIGTERM);
        }
        while (!stopping && !exhausted && running.size() < parallel) {
            std::optional<PointJob> job = next();
            if (!job) {
                exhausted = true;
                break;
            }
            if (on_start) on_start(*job);
            const auto start = Clock::now();
            {
                std::error_code ec;
                fs::create_directories(job->log.parent_path(), ec);
                std::ofstream header(job->log, std::ios::trunc);
                header << "# tumble sweep:";
                for (const std::string& a : job->argv) header << ' ' << a;
                header << '\n';
            }
            try {
                const auto pid = static_cast<pid_t>(spawn_process(job->argv, job->log));
                running.push_back({std::move(*job), pid, start});
            } catch (const Error& e) {
                std::ofstream(job->log, std::ios::app) << e.what() << '\n';
                finish(*job, 127, start);
            }
        }
        bool reaped = false;
        for (std::size_t k = 0; k < running.size();) {
            int status = 0;
            const pid_t r = waitpid(running[k].pid, &status, WNOHANG);
            if (r == running[k].pid || (r < 0 && errno != EINTR)) {
                finish(running[k].job, r < 0 ? 255 : decode_wait_status(status), running[k].start);
                running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
                reaped = true;
            } else {
                ++k;
            }
        }
        if (!reaped && !running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return outcomes;
}

std::vector<PointOutcome> run_jobs(const std::vector<PointJob>& jobs, unsigned parallel,
                                   const std::function<void(const PointJob&)>& on_start,
                                   const std::function<void(const PointJob&, const PointOutcome&)>& on_finish,
                                   const std::function<bool()>& stop) {
    std::size_t next = 0;
    return run_jobs([&]() -> std::optional<PointJob> { return next < jobs.size() ? std::optional(jobs[next++]) : std::nullopt; },
                    parallel, on_start, on_finish, stop);
}

// ============================================================ aggregation

std::vector<std::string> components_of_mode(const std::string& mode) {
    if (mode == "self") return {"left", "right"};
    return {"material-1", "material-2"};
}

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Empty for undefined numbers: a CSV reader makes them NaN.
std::string cell(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string(); }

bool has_numbers(const PointResult& r) { return r.state == PointState::finished && r.note.empty(); }

}  // namespace

PointResult read_point_result(const SweepPoint& p) {
    const PointState state = point_state(p.directory);
    if (state == PointState::failed) {
        std::ifstream in(p.directory / point_failed_file);
        std::string line;
        std::getline(in, line);
        PointResult r{p, state, "failed (" + line + "); log: " + (p.directory / point_log_file).string(), {},
                      nan, nan, nan, nan, nan, nan};
        return r;
    }
    if (state != PointState::finished)
        return {p, state, std::string(to_string(state)) + ": no summary.json", {}, nan, nan, nan, nan, nan, nan};
    const fs::path file = p.directory / point_summary_file;
    try {
        return point_result_from_summary(p, read_text_file(file), file.string());
    } catch (const Error& e) {
        return {p, state, std::string("unreadable summary.json: ") + e.what(), {}, nan, nan, nan, nan, nan, nan};
    }
}

PointResult failed_point_result(const SweepPoint& p, int exit_code, const std::string& where) {
    return {p, PointState::failed,
            fmt::format("failed ({}exit code {}); log: {}", where, exit_code, (p.directory / point_log_file).string()),
            {}, nan, nan, nan, nan, nan, nan};
}

PointResult point_result_from_summary(const SweepPoint& p, const std::string& text, const std::string& source) {
    PointResult r{p, PointState::finished, "", {}, nan, nan, nan, nan, nan, nan};
    try {
        const Json j = parse_json(text, source);
        if (!j.is_object()) throw Error(source + ": not a JSON object");
        auto num = [](const Json& o, std::string_view key) { return json_number(o, key).value_or(nan); };
        auto is_true = [](const Json& o, const char* key) {
            const auto it = o.find(key);
            return it != o.end() && it->is_boolean() && it->get<bool>();
        };
        auto name_of = [&](const Json& o) {
            const auto it = o.find("name");
            return it != o.end() && it->is_string() ? it->get<std::string>() : std::string();
        };
        const auto comps = j.find("components");
        if (comps == j.end() || !comps->is_array()) throw Error(source + ": no \"components\" array");
        for (const Json& c : *comps) {
            const std::string name = name_of(c);
            if (name.empty()) throw Error(source + ": a component without a name");
            // D where determined, else its best estimate (null D; a summary
            // written before held the best estimate in D itself).
            const double D = std::isfinite(num(c, "D")) ? num(c, "D") : num(c, "D_best_estimate");
            PointResult::Component k{D, num(c, "D_stderr"), num(c, "D_one_term"), is_true(c, "determined"), nan};
            // The grains' MSD D and the free-amplitude Hogg D, where determined.
            if (const auto m = c.find("msd"); m != c.end() && is_true(*m, "determined"))
                k.msd_D = num(*m, "D"), k.msd_lo = num(*m, "D_lo"), k.msd_hi = num(*m, "D_hi");
            if (const auto h = c.find("hogg_free"); h != c.end() && is_true(*h, "determined"))
                k.hogg_D = num(*h, "D"), k.hogg_lo = num(*h, "D_lo"), k.hogg_hi = num(*h, "D_hi");
            r.components[name] = k;
        }
        if (const auto depth = j.find("depth_mobility"); depth != j.end() && depth->is_array())
            for (const Json& c : *depth)
                if (auto it = r.components.find(name_of(c)); it != r.components.end())
                    it->second.surface_share = num(c, "surface_share");
        r.ke_ratio_total = num(j, "kinetic_energy_ratio_total");
        r.ke_ratio_total_ref = num(j, "kinetic_energy_ratio_total_equal_velocity");
        r.ke_ratio_per_grain = num(j, "kinetic_energy_ratio_per_grain");
        r.ke_ratio_per_grain_ref = num(j, "kinetic_energy_ratio_per_grain_equal_velocity");
        r.angle_of_repose = num(j, "angle_of_repose");
        r.grain_updates_per_second = num(j, "grain_updates_per_second");
    } catch (const Error& e) {
        r.note = std::string("unreadable summary.json: ") + e.what();
    }
    return r;
}

std::size_t write_sweep_tables(const fs::path& directory, const std::vector<PointResult>& results) {
    // Component columns: those of the modes present, in order of appearance.
    std::vector<std::string> components;
    for (const PointResult& r : results)
        for (const std::string& c : components_of_mode(r.point.mode))
            if (std::find(components.begin(), components.end(), c) == components.end()) components.push_back(c);
    const auto component = [](const PointResult& r, const std::string& c) -> const PointResult::Component* {
        auto it = r.components.find(c);
        return it == r.components.end() ? nullptr : &it->second;
    };

    std::size_t missing = 0;
    {
        std::ostringstream out;
        out << "mode,shear_model,friction_normal,tangential_stiffness,ends,walls,omega,froude,seed,revolutions,grains";
        for (const std::string& c : components)
            out << fmt::format(",D_{0},D_stderr_{0},D_one_term_{0},determined_{0},surface_share_{0},D_msd_{0},D_msd_lo_{0},"
                               "D_msd_hi_{0},D_hogg_free_{0},D_hogg_free_lo_{0},D_hogg_free_hi_{0}",
                               column_name(c));
        out << ",ke_ratio_total,ke_ratio_total_ref,ke_ratio_per_grain,ke_ratio_per_grain_ref,angle_of_repose,"
               "grain_updates_per_second,status\n";
        for (const PointResult& r : results) {
            const SweepPoint& p = r.point;
            const bool ok = has_numbers(r);
            if (!ok) ++missing;
            out << fmt::format("{},{},{},{},{},{},{},{},{},{},{}", p.mode, p.shear, p.friction_normal,
                               p.tangential_stiffness, p.periodic_axis ? "periodic" : "caps", p.walls, p.omega, p.froude,
                               p.seed, p.revolutions, p.grains);
            for (const std::string& c : components) {
                const PointResult::Component* k = ok ? component(r, c) : nullptr;
                if (k)
                    out << fmt::format(",{},{},{},{},{},{},{},{},{},{},{}", cell(k->D), cell(k->D_stderr),
                                       cell(k->D_one_term), k->determined ? "true" : "false", cell(k->surface_share),
                                       cell(k->msd_D), cell(k->msd_lo), cell(k->msd_hi), cell(k->hogg_D),
                                       cell(k->hogg_lo), cell(k->hogg_hi));
                else
                    out << ",,,,,,,,,,,";
            }
            for (double v : {r.ke_ratio_total, r.ke_ratio_total_ref, r.ke_ratio_per_grain, r.ke_ratio_per_grain_ref,
                             r.angle_of_repose, r.grain_updates_per_second})
                out << ',' << (ok ? cell(v) : std::string());
            out << ',' << (ok ? "finished" : to_string(r.state)) << '\n';
        }
        std::ofstream f(directory / "sweep.csv", std::ios::trunc);
        f << out.str();
        if (!f) throw Error((directory / "sweep.csv").string() + ": cannot write");
    }

    {
        // Quantities averaged over the seeds of one (mode, omega): D and
        // D_one_term over the seeds where D was determined, the rest over all
        // finished seeds with a defined value.
        using Get = std::function<double(const PointResult&)>;
        std::vector<std::pair<std::string, Get>> quantities;
        for (const std::string& c : components) {
            quantities.emplace_back("D_msd_" + column_name(c), [c, component](const PointResult& r) {
                const auto* k = component(r, c);
                return k ? k->msd_D : nan;
            });
            quantities.emplace_back("D_hogg_free_" + column_name(c), [c, component](const PointResult& r) {
                const auto* k = component(r, c);
                return k ? k->hogg_D : nan;
            });
            quantities.emplace_back("D_" + column_name(c), [c, component](const PointResult& r) {
                const auto* k = component(r, c);
                return k && k->determined ? k->D : nan;
            });
            quantities.emplace_back("D_one_term_" + column_name(c), [c, component](const PointResult& r) {
                const auto* k = component(r, c);
                return k && k->determined ? k->D_one_term : nan;
            });
            quantities.emplace_back("surface_share_" + column_name(c), [c, component](const PointResult& r) {
                const auto* k = component(r, c);
                return k ? k->surface_share : nan;
            });
        }
        quantities.emplace_back("ke_ratio_total", [](const PointResult& r) { return r.ke_ratio_total; });
        quantities.emplace_back("ke_ratio_total_ref", [](const PointResult& r) { return r.ke_ratio_total_ref; });
        quantities.emplace_back("ke_ratio_per_grain", [](const PointResult& r) { return r.ke_ratio_per_grain; });
        quantities.emplace_back("ke_ratio_per_grain_ref",
                                [](const PointResult& r) { return r.ke_ratio_per_grain_ref; });
        quantities.emplace_back("angle_of_repose", [](const PointResult& r) { return r.angle_of_repose; });
        quantities.emplace_back("grain_updates_per_second",
                                [](const PointResult& r) { return r.grain_updates_per_second; });

        std::ostringstream out;
        out << "mode,omega,froude,seeds,finished";
        for (const auto& [name, get] : quantities) out << fmt::format(",{0}_mean,{0}_std,{0}_n,{0}_lo,{0}_hi", name);
        out << '\n';
        std::vector<bool> done(results.size(), false);
        for (std::size_t i = 0; i < results.size(); ++i) {
            if (done[i]) continue;
            std::vector<const PointResult*> group;
            for (std::size_t k = i; k < results.size(); ++k)
                if (!done[k] && results[k].point.mode == results[i].point.mode &&
                    results[k].point.omega == results[i].point.omega) {
                    group.push_back(&results[k]);
                    done[k] = true;
                }
            std::size_t finished = 0;
            for (const PointResult* r : group) finished += has_numbers(*r);
            const SweepPoint& p = results[i].point;
            out << fmt::format("{},{},{},{},{}", p.mode, p.omega, p.froude, group.size(), finished);
            for (const auto& [name, get] : quantities) {
                std::vector<double> v;
                for (const PointResult* r : group)
                    if (has_numbers(*r))
                        if (const double x = get(*r); std::isfinite(x)) v.push_back(x);
                double mean = nan, sd = nan;
                if (!v.empty()) {
                    mean = 0.0;
                    for (double x : v) mean += x;
                    mean /= static_cast<double>(v.size());
                }
                if (v.size() > 1) {
                    double ss = 0.0;
                    for (double x : v) ss += (x - mean) * (x - mean);
                    sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
                }
                // The seed is the statistical unit: Student's t interval of
                // the mean over seeds (none from fewer than 3).
                const analysis::Interval ci = analysis::independent_mean(v).interval;
                out << fmt::format(",{},{},{},{},{}", cell(mean), cell(sd), v.size(), cell(ci.lo), cell(ci.hi));
            }
            out << '\n';
        }
        std::ofstream f(directory / "sweep_summary.csv", std::ios::trunc);
        f << out.str();
        if (!f) throw Error((directory / "sweep_summary.csv").string() + ": cannot write");
    }
    return missing;
}

}  // namespace tumble::io
