// SPDX-License-Identifier: MIT
#include "io/output.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>
#include <fmt/os.h>

#include "tumble/core/error.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

std::ofstream open_for_writing(const fs::path& file) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(file.string() + ": cannot open for writing");
    return out;
}

void check_written(std::ofstream& out, const fs::path& file) {
    out.flush();
    if (!out) throw Error(file.string() + ": write failed (disk full or file system error)");
}

TimeSeriesWriter::TimeSeriesWriter(const fs::path& file, const std::vector<Material>& materials)
    : path_(file), out_(open_for_writing(file)) {
    out_ << "time,step,kinetic_translational,kinetic_rotational,contact_energy,contacts,max_overlap_ratio,"
            "neighbor_builds";
    for (const Material& m : materials)
        out_ << ",particles_" << m.name << ",kinetic_translational_" << m.name << ",kinetic_rotational_" << m.name;
    out_ << '\n';
    check_written(out_, path_);
}

void TimeSeriesWriter::write(const Observables& o) {
    out_ << fmt::format("{},{},{},{},{},{},{},{}", o.time, o.step, o.kinetic_translational, o.kinetic_rotational,
                        o.contact_energy, o.contacts, o.max_overlap_ratio, o.neighbor_builds);
    for (const MaterialEnergies& e : o.per_material)
        out_ << fmt::format(",{},{},{}", e.particles, e.kinetic_translational, e.kinetic_rotational);
    out_ << '\n';
    check_written(out_, path_);
}

fs::path write_snapshot(const fs::path& directory, int number, const Simulation& sim) {
    const fs::path folder = directory / "snapshots";
    fs::create_directories(folder);
    const fs::path file = folder / fmt::format("{:06d}.csv", number);
    std::ofstream out = open_for_writing(file);
    const ParticleStore& p = sim.particles();
    std::vector<std::size_t> by_id(p.size());
    std::iota(by_id.begin(), by_id.end(), std::size_t{0});
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    out << fmt::format("# time = {} s, step = {}\n", sim.time(), sim.step_count());
    out << "id,x,y,z,vx,vy,vz,wx,wy,wz,radius,material,tag,kinematic\n";
    for (std::size_t i : by_id) {
        const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
        out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", p.id[i], x.x, x.y, x.z, v.x, v.y, v.z, w.x,
                           w.y, w.z, p.radius[i], sim.scenario().materials[p.material[i]].name, p.tag[i],
                           p.is_kinematic(i) ? 1 : 0);
    }
    check_written(out, file);
    return file;
}

void prepare_output_directory(const fs::path& directory, bool overwrite) {
    std::error_code ec;
    if (fs::exists(directory / "time_series.csv", ec) && !overwrite)
        throw Error(directory.string() + ": holds the output of an earlier run; choose another directory or pass --force");
    if (overwrite) fs::remove_all(directory / "snapshots", ec);
    fs::create_directories(directory, ec);
    if (ec) throw Error(directory.string() + ": cannot create the output directory: " + ec.message());
}

void write_run_json(const fs::path& file, const Simulation& sim, const RunSummary& s) {
    const TimeStepReport& t = sim.time_step_report();
    const double updates = s.wall_seconds > 0.0 ? static_cast<double>(s.free_particles) * s.steps / s.wall_seconds : 0.0;
    std::ofstream out = open_for_writing(file);
    out << "{\n"
        << fmt::format("  \"tumble_version\": \"{}\",\n", TUMBLE_VERSION)
        << fmt::format("  \"scenario\": \"{}\",\n", s.scenario_file)
        << fmt::format("  \"seed\": {},\n", s.seed)
        << fmt::format("  \"particles\": {},\n  \"free_particles\": {},\n", s.particles, s.free_particles)
        << fmt::format("  \"duration\": {},\n  \"steps\": {},\n", s.duration, s.steps)
        << fmt::format("  \"dt\": {},\n  \"dt_automatic\": {},\n", t.dt, t.automatic ? "true" : "false")
        << fmt::format("  \"dt_recommended\": {},\n  \"dt_maximum\": {},\n", t.recommended, t.maximum)
        << fmt::format("  \"collision_time\": {},\n  \"viscous_time\": {},\n  \"rayleigh_time\": {},\n",
                       t.collision_time, t.viscous_time, t.rayleigh_time)
        << fmt::format("  \"neighbor_skin\": {},\n  \"neighbor_builds\": {},\n", sim.neighbors().skin(),
                       sim.neighbors().builds())
        << fmt::format("  \"threads\": {},\n", sim.threads())
        << fmt::format("  \"wall_seconds\": {},\n  \"updates_per_second\": {}\n", s.wall_seconds, updates) << "}\n";
    check_written(out, file);
}

}  // namespace tumble::io
