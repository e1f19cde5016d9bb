// SPDX-License-Identifier: MIT
#include "io/output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <numeric>

#include <fmt/format.h>
#include <fmt/os.h>

#include "io/csv_table.hpp"
#include "io/json.hpp"
#include "tumble/core/error.hpp"
#include "tumble/core/isa.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

std::ofstream open_for_writing(const fs::path& file) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(file.string() + ": cannot open for writing");
    return out;
}

std::ofstream open_for_appending(const fs::path& file) {
    std::ofstream out(file, std::ios::binary | std::ios::app);
    if (!out) throw Error(file.string() + ": cannot open for appending");
    return out;
}

namespace {
[[noreturn]] void fail_with_errno(const fs::path& file, const char* what) {
    throw Error(fmt::format("{}: {} failed: {}", file.string(), what, std::strerror(errno)));
}
}  // namespace

namespace {
// A test hook (tests/unit/test_safety.cpp): with TUMBLE_TEST_KILL_AT_RENAME=N
// in the environment, the process kills itself (SIGKILL) just before its Nth
// rename of a file into place by write_file_atomically, as a power cut or
// kill -9 at that moment would.
void kill_point_for_tests() {
    static const long kill_at = [] {
        const char* n = std::getenv("TUMBLE_TEST_KILL_AT_RENAME");
        return n ? std::atol(n) : 0L;
    }();
    static std::atomic<long> renames{0};
    if (kill_at > 0 && ++renames == kill_at) ::raise(SIGKILL);
}
}  // namespace

namespace {
// Writes `bytes` into file.tmp and renames it over `file`; with `to_disk`,
// the file and then the directory are flushed to the disk (fsync) as well.
void replace_file(const fs::path& file, std::span<const std::string_view> parts, bool to_disk) {
    const fs::path temporary = file.string() + ".tmp";
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail_with_errno(temporary, "opening for writing");
    auto give_up = [&](const char* what) {
        const int saved = errno;
        ::close(fd);
        ::unlink(temporary.c_str());
        errno = saved;
        fail_with_errno(temporary, what);
    };
    for (const std::string_view bytes : parts)
        for (std::size_t done = 0; done < bytes.size();) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) give_up("writing (disk full?)");
            done += static_cast<std::size_t>(n);
        }
    if (to_disk && ::fsync(fd) != 0) give_up("flushing to disk");
    if (::close(fd) != 0) {
        const int saved = errno;
        ::unlink(temporary.c_str());
        errno = saved;
        fail_with_errno(temporary, "closing");
    }
    if (to_disk) kill_point_for_tests();
    if (::rename(temporary.c_str(), file.c_str()) != 0) {
        const int saved = errno;
        ::unlink(temporary.c_str());
        errno = saved;
        fail_with_errno(file, "renaming into place");
    }
    if (!to_disk) return;
    const int dir = ::open(file.parent_path().empty() ? "." : file.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        ::fsync(dir);  // the rename itself reaches the disk
        ::close(dir);
    }
}
}  // namespace

void write_file_atomically(const fs::path& file, std::string_view bytes) { replace_file(file, {&bytes, 1}, true); }

void write_file_whole(const fs::path& file, std::string_view bytes) { replace_file(file, {&bytes, 1}, false); }

void write_file_whole(const fs::path& file, std::span<const std::string_view> parts) {
    replace_file(file, parts, false);
}

void check_written(std::ofstream& out, const fs::path& file) {
    out.flush();
    if (!out) throw Error(file.string() + ": write failed (disk full or file system error)");
}

TimeSeriesWriter::TimeSeriesWriter(const fs::path& file, const Scenario& scenario, bool continuing)
    : path_(file), out_(continuing ? open_for_appending(file) : open_for_writing(file)) {
    if (continuing) return;
    out_ << "time,step,kinetic_translational,kinetic_rotational,contact_energy,contacts,max_overlap_ratio,"
            "neighbor_builds";
    for (const Material& m : scenario.materials)
        out_ << fmt::format(",particles_{0},kinetic_translational_{0},kinetic_rotational_{0}", column_name(m.name));
    for (const Wall& w : scenario.walls)
        out_ << fmt::format(",wall_{0}_fx,wall_{0}_fy,wall_{0}_fz,wall_{0}_tx,wall_{0}_ty,wall_{0}_tz", column_name(w.name));
    out_ << '\n';
    check_written(out_, path_);
}

void TimeSeriesWriter::write(const Observables& o) {
    out_ << fmt::format("{},{},{},{},{},{},{},{}", o.time, o.step, o.kinetic_translational, o.kinetic_rotational,
                        o.contact_energy, o.contacts, o.max_overlap_ratio, o.neighbor_builds);
    for (const MaterialEnergies& e : o.per_material)
        out_ << fmt::format(",{},{},{}", e.particles, e.kinetic_translational, e.kinetic_rotational);
    for (const WallLoad& l : o.wall_loads)
        out_ << fmt::format(",{},{},{},{},{},{}", l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z);
    out_ << '\n';
    check_written(out_, path_);
}

std::vector<std::size_t> order_by_id(const ParticleStore& p) {
    std::vector<std::size_t> by_id(p.size());
    std::iota(by_id.begin(), by_id.end(), std::size_t{0});
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    return by_id;
}

fs::path write_snapshot(const fs::path& directory, int number, const Simulation& sim) {
    return write_snapshot(directory, number, snapshot_of(sim));
}

fs::path write_snapshot(const fs::path& directory, int number, const SnapshotData& snapshot) {
    const fs::path folder = directory / "snapshots";
    fs::create_directories(folder);
    const fs::path file = folder / fmt::format("{:06d}.csv", number);
    const ParticleStore& p = snapshot.particles;
    // The time and step on every row, so that snapshots concatenated stay apart.
    const std::string when = fmt::format("{},{}", snapshot.time, snapshot.step);
    fmt::memory_buffer out;
    fmt::format_to(fmt::appender(out), "time,step,id,x,y,z,vx,vy,vz,wx,wy,wz,radius,material,tag,kinematic\n");
    for (std::size_t i : order_by_id(p)) {
        const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
        fmt::format_to(fmt::appender(out), "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", when, p.id[i], x.x, x.y,
                       x.z, v.x, v.y, v.z, w.x, w.y, w.z, p.radius[i],
                       snapshot.material_names[static_cast<std::size_t>(p.material[i])], p.tag[i],
                       p.is_kinematic(i) ? 1 : 0);
    }
    write_file_whole(file, {out.data(), out.size()});
    return file;
}

fs::path default_movie_file(const fs::path& directory) {
    return directory / (fs::weakly_canonical(fs::absolute(directory)).filename().string() + ".mp4");
}

RunLock prepare_output_directory(const fs::path& directory, bool overwrite) {
    std::error_code ec;
    const bool written_by_tumble = fs::exists(directory / run_lock_file, ec);
    fs::create_directories(directory, ec);
    if (ec) throw Error(directory.string() + ": cannot create the output directory: " + ec.message());
    RunLock lock(directory);
    if (fs::exists(directory / "time_series.csv", ec) && !overwrite)
        throw Error(directory.string() + ": holds the output of an earlier run; choose another directory or pass --force");
    if (!written_by_tumble)
        for (const char* name : {"time_series.csv", "snapshots", "checkpoints"})
            if (fs::exists(directory / name, ec))
                throw Error((directory / name).string() + ": exists, but tumble did not write " + directory.string() +
                            " (it has no " + run_lock_file + "); choose another directory");
    if (overwrite) {
        std::vector<fs::path> files;
        for (std::string_view name : run_files) {
            files.push_back(directory / name);
            files.push_back(directory / (std::string(name) + ".tmp"));  // of a write cut short
        }
        files.push_back(default_movie_file(directory));
        for (const fs::path& file : files) {
            fs::remove_all(file, ec);
            if (ec) throw Error(file.string() + ": cannot remove the earlier run's file: " + ec.message());
        }
    }
    return lock;
}

void write_run_json(const fs::path& file, const Simulation& sim, const RunSummary& s) {
    const TimeStepReport& t = sim.time_step_report();
    const double updates = s.wall_seconds > 0.0 ? static_cast<double>(s.free_particles) * s.steps / s.wall_seconds : 0.0;
    write_json_file(file, Json{{"tumble_version", TUMBLE_VERSION},
                               {"scenario", s.scenario_file},
                               {"seed", s.seed},
                               {"particles", s.particles},
                               {"free_particles", s.free_particles},
                               {"duration", s.duration},
                               {"steps", s.steps},
                               {"dt", t.dt},
                               {"dt_automatic", t.automatic},
                               {"dt_recommended", t.recommended},
                               {"dt_maximum", t.maximum},
                               {"collision_time", t.collision_time},
                               {"viscous_time", t.viscous_time},
                               {"creep_time", t.creep_time},
                               {"rayleigh_time", t.rayleigh_time},
                               {"neighbor_skin", sim.neighbors().skin()},
                               {"neighbor_builds", sim.neighbors().builds()},
                               {"threads", sim.threads()},
                               {"isa", isa_description()},
                               {"wall_seconds", s.wall_seconds},
                               {"updates_per_second", updates},
                               {"time_by_phase", step_times_json(s.time_by_phase)}});
}

}  // namespace tumble::io
