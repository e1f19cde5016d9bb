// SPDX-License-Identifier: MIT
#include "io/checkpoint.hpp"

#include "tumble/sim/simulation.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "io/binary.hpp"
#include "io/output.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

// Stored as they lie in memory (binary.hpp): no padding inside.
static_assert(sizeof(Vec3) == 3 * sizeof(double));
static_assert(sizeof(ContactHistory) == 2 * sizeof(double) + sizeof(Vec3));
static_assert(sizeof(PairProperties) == 2 * sizeof(double));
static_assert(sizeof(RigidMotion) == 3 * sizeof(Vec3) + sizeof(double));
static_assert(sizeof(MotionClock) == sizeof(RigidMotion) + sizeof(double));

constexpr std::string_view magic = "TUMBLECK";
constexpr std::size_t header_size = magic.size() + sizeof(std::uint32_t) + sizeof(std::uint64_t);

// The message tag of the ranks' accounts of their files (load_shared_checkpoint),
// apart from those of the slabs (sim/slabs.cpp).
constexpr int checkpoint_agreement_tag = 200;

// ---- the record

void put_record(ByteWriter& w, const CheckpointRecord& r) {
    w.put(static_cast<std::uint64_t>(r.values().size()));
    for (const auto& [key, value] : r.values()) {
        w.put(key);
        w.put(static_cast<std::uint8_t>(value.index()));
        if (const auto* d = std::get_if<double>(&value)) w.put(*d);
        if (const auto* i = std::get_if<std::int64_t>(&value)) w.put(*i);
        if (const auto* s = std::get_if<std::string>(&value)) w.put(*s);
        if (const auto* v = std::get_if<std::vector<double>>(&value)) w.put_array(*v);
    }
}

CheckpointRecord get_record(ByteReader& r) {
    CheckpointRecord record;
    const std::size_t n = r.count(9, "record");
    for (std::size_t k = 0; k < n; ++k) {
        std::string key = r.get_string("record key");
        switch (r.get<std::uint8_t>("record value kind")) {
            case 0: record.set(key, r.get<double>("record number")); break;
            case 1: record.set(key, r.get<std::int64_t>("record integer")); break;
            case 2: record.set(key, r.get_string("record text")); break;
            case 3: record.set(key, r.get_array<double>("record numbers")); break;
            default: r.fail("record value \"" + key + "\": unknown kind");
        }
    }
    return record;
}

// ---- the scenario

void put_scenario(ByteWriter& w, const Scenario& s) {
    w.put(static_cast<std::uint64_t>(s.materials.size()));
    for (const Material& m : s.materials) {
        w.put(m.name);
        for (double v : {m.E, m.G, m.nu, m.xi, m.eta, m.rho, m.radius}) w.put(v);
    }
    w.put(static_cast<std::uint64_t>(s.pair_properties.size()));
    for (const auto& row : s.pair_properties) w.put_array(row);
    w.put(s.model.elastic);
    w.put(s.model.viscous);
    w.put(s.model.attraction);
    w.put(static_cast<std::uint8_t>(s.model.shear));
    w.put(s.model.twisting);
    w.put(static_cast<std::uint8_t>(s.model.friction_normal));
    w.put(static_cast<std::uint8_t>(s.model.tangential_stiffness));
    w.put(s.model.slip_velocity_regularisation);
    w.put(s.domain.lo);
    w.put(s.domain.hi);
    for (int k = 0; k < 3; ++k) w.put(s.domain.periodic[k]);
    for (int k = 0; k < 3; ++k) w.put(s.domain.walls[k]);
    w.put(s.domain.wall_material);
    w.put(s.gravity);
    w.put(s.time_step.dt);
    w.put(s.time_step.reference_speed);
    w.put(s.time_step.allow_unsafe);
    w.put(s.neighbor.skin);
    w.put(static_cast<std::int32_t>(s.neighbor.sort_every));
    w.put_array(s.motions);
    w.put(static_cast<std::uint64_t>(s.walls.size()));
    for (const Wall& wall : s.walls) {
        w.put(wall.name);
        w.put(static_cast<std::uint8_t>(wall.shape));
        for (const Vec3& v : {wall.point, wall.normal, wall.edge}) w.put(v);
        for (double v : {wall.half_width, wall.half_height, wall.radius, wall.hole_radius, wall.end_radius, wall.length})
            w.put(v);
        w.put(wall.inside);
        w.put(wall.material);
        w.put(wall.motion);
        w.put(wall.mesh);
        w.put(wall.sided);
    }
    w.put(static_cast<std::uint64_t>(s.meshes.size()));
    for (const TriangleMesh& m : s.meshes) {
        w.put_array(m.vertices);
        w.put_array(m.triangles);
    }
    w.put(static_cast<std::uint64_t>(s.particles.size()));
    for (const ParticleSpec& p : s.particles) {
        w.put(p.position);
        w.put(p.velocity);
        w.put(p.angular_velocity);
        w.put(p.radius);
        w.put(p.material);
        w.put(p.motion);
        w.put(p.tag);
    }
    w.put(static_cast<std::uint64_t>(s.insertions.size()));
    for (const Insertion& q : s.insertions) {
        for (const Vec3& v : {q.lo, q.hi, q.velocity}) w.put(v);
        for (std::int64_t v : {q.count, q.batch}) w.put(v);
        for (double v : {q.start, q.every, q.radius_min, q.radius_max}) w.put(v);
        for (std::int32_t v : {q.material, q.tag}) w.put(v);
        w.put(q.seed);
    }
}

Scenario get_scenario(ByteReader& r, std::uint32_t version) {
    Scenario s;
    s.materials.resize(r.count(8 + 7 * sizeof(double), "materials"));
    for (Material& m : s.materials) {
        m.name = r.get_string("material name");
        for (double* v : {&m.E, &m.G, &m.nu, &m.xi, &m.eta, &m.rho, &m.radius}) *v = r.get<double>("material");
    }
    s.pair_properties.resize(r.count(8, "pair table"));
    for (auto& row : s.pair_properties) row = r.get_array<PairProperties>("pair table row");
    s.model.elastic = r.get_bool("model");
    s.model.viscous = r.get_bool("model");
    s.model.attraction = r.get_bool("model");
    const auto shear = r.get<std::uint8_t>("model shear");
    if (shear > static_cast<std::uint8_t>(ShearModel::Spring)) r.fail("model shear: unknown shear model");
    s.model.shear = static_cast<ShearModel>(shear);
    s.model.twisting = r.get_bool("model");
    const auto friction_normal = r.get<std::uint8_t>("model friction normal");
    if (friction_normal > static_cast<std::uint8_t>(FrictionNormal::Jkr))
        r.fail("model friction normal: unknown choice");
    s.model.friction_normal = static_cast<FrictionNormal>(friction_normal);
    if (version >= 6) {  // before: the paper's stiffness, the only one
        const auto stiffness = r.get<std::uint8_t>("model tangential stiffness");
        if (stiffness > static_cast<std::uint8_t>(TangentialStiffness::Mindlin))
            r.fail("model tangential stiffness: unknown choice");
        s.model.tangential_stiffness = static_cast<TangentialStiffness>(stiffness);
    }
    s.model.slip_velocity_regularisation = r.get<double>("model");
    s.domain.lo = r.get<Vec3>("domain");
    s.domain.hi = r.get<Vec3>("domain");
    for (int k = 0; k < 3; ++k) s.domain.periodic[k] = r.get_bool("domain periodic");
    for (int k = 0; k < 3; ++k) s.domain.walls[k] = r.get_bool("domain walls");
    s.domain.wall_material = r.get<std::int32_t>("domain wall material");
    s.gravity = r.get<Vec3>("gravity");
    s.time_step.dt = r.get<double>("time step");
    s.time_step.reference_speed = r.get<double>("time step");
    s.time_step.allow_unsafe = r.get_bool("time step");
    s.neighbor.skin = r.get<double>("neighbour settings");
    s.neighbor.sort_every = r.get<std::int32_t>("neighbour settings");
    s.motions = r.get_array<RigidMotion>("motions");
    if (version >= 7) {  // before: no walls besides the box's
        const std::size_t mesh_index = version >= 9 ? sizeof(std::int32_t) + 1 : version >= 8 ? sizeof(std::int32_t) : 0;
        s.walls.resize(
            r.count(8 + 1 + 3 * sizeof(Vec3) + 6 * sizeof(double) + 1 + 2 * sizeof(std::int32_t) + mesh_index, "walls"));
        for (Wall& wall : s.walls) {
            wall.name = r.get_string("wall name");
            const auto shape = r.get<std::uint8_t>("wall shape");
            const auto last = version >= 8 ? WallShape::mesh : WallShape::cone;  // before 8: no meshes
            if (shape > static_cast<std::uint8_t>(last)) r.fail("wall shape: unknown shape");
            wall.shape = static_cast<WallShape>(shape);
            for (Vec3* v : {&wall.point, &wall.normal, &wall.edge}) *v = r.get<Vec3>("wall");
            for (double* v : {&wall.half_width, &wall.half_height, &wall.radius, &wall.hole_radius, &wall.end_radius,
                              &wall.length})
                *v = r.get<double>("wall");
            wall.inside = r.get_bool("wall");
            wall.material = r.get<std::int32_t>("wall material");
            wall.motion = r.get<std::int32_t>("wall motion");
            if (version >= 8) wall.mesh = r.get<std::int32_t>("wall mesh");
            if (version >= 9) wall.sided = r.get_bool("wall side");
        }
    }
    if (version >= 8) {  // before: no meshes
        s.meshes.resize(r.count(2 * 8, "meshes"));
        for (TriangleMesh& m : s.meshes) {
            m.vertices = r.get_array<Vec3>("mesh vertices");
            m.triangles = r.get_array<std::array<std::uint32_t, 3>>("mesh triangles");
        }
    }
    s.particles.resize(r.count(3 * sizeof(Vec3) + sizeof(double) + 3 * sizeof(std::int32_t), "particles"));
    for (ParticleSpec& p : s.particles) {
        p.position = r.get<Vec3>("particle");
        p.velocity = r.get<Vec3>("particle");
        p.angular_velocity = r.get<Vec3>("particle");
        p.radius = r.get<double>("particle");
        p.material = r.get<std::int32_t>("particle");
        p.motion = r.get<std::int32_t>("particle");
        p.tag = r.get<std::int32_t>("particle");
    }
    if (version >= 9) {  // before: nothing poured in
        s.insertions.resize(r.count(3 * sizeof(Vec3) + 2 * 8 + 4 * sizeof(double) + 2 * sizeof(std::int32_t) + 8,
                                    "insertions"));
        for (Insertion& q : s.insertions) {
            for (Vec3* v : {&q.lo, &q.hi, &q.velocity}) *v = r.get<Vec3>("insertion");
            for (std::int64_t* v : {&q.count, &q.batch}) *v = r.get<std::int64_t>("insertion");
            for (double* v : {&q.start, &q.every, &q.radius_min, &q.radius_max}) *v = r.get<double>("insertion");
            for (std::int32_t* v : {&q.material, &q.tag}) *v = r.get<std::int32_t>("insertion");
            q.seed = r.get<std::uint64_t>("insertion");
        }
    }
    return s;
}

// ---- the engine state

void put_state(ByteWriter& w, const SimulationState& s) {
    const ParticleStore& p = s.particles;
    w.put_array(p.id);
    for (const auto* field : {&p.position, &p.velocity, &p.angular_velocity, &p.force, &p.torque}) w.put_array(*field);
    for (const auto* field : {&p.radius, &p.inv_mass, &p.inv_inertia, &p.mass}) w.put_array(*field);
    for (const auto* field : {&p.material, &p.motion, &p.tag}) w.put_array(*field);
    w.put_array(p.reference_position);
    w.put_array(p.image_shift);
    w.put_array(s.neighbors.pairs.first);
    w.put_array(s.neighbors.pairs.second);
    w.put_array(s.neighbors.pairs.image);
    w.put_array(s.neighbors.pairs.histories());
    w.put_array(s.neighbors.position_at_build);
    w.put(s.neighbors.builds);
    w.put_array(s.wall_history);
    w.put_array(s.wall_feature);
    w.put_array(s.motions);
    w.put_array(s.inserted);
    w.put(s.dt);
    w.put(s.time);
    w.put(s.step);
    w.put(static_cast<std::uint64_t>(s.owned));
    w.put_array(s.slabs.cuts);
    for (int side = 0; side < 2; ++side) {
        w.put_array(s.slabs.send[static_cast<std::size_t>(side)]);
        w.put(static_cast<std::uint64_t>(s.slabs.receive_begin[static_cast<std::size_t>(side)]));
        w.put(static_cast<std::uint64_t>(s.slabs.receive_count[static_cast<std::size_t>(side)]));
    }
    w.put(static_cast<std::int32_t>(s.ranks));
}

// The contact histories of a file of format `version`. Format 2 kept no
// viscous force: its contacts resume with 0, so the dashpot's first step
// (integrate/dashpot.hpp) sees the whole predicted velocity.
std::vector<ContactHistory> get_histories(ByteReader& r, std::uint32_t version, const char* field) {
    if (version != 2) return r.get_array<ContactHistory>(field);
    struct Version2 {
        Vec3 slip;
        double angular_slip;
    };
    std::vector<ContactHistory> histories;
    for (const Version2& h : r.get_array<Version2>(field)) histories.push_back({h.slip, h.angular_slip, 0.0});
    return histories;
}

// cuts: the state has the slab cuts (format 5, and some files of format 4:
// checkpoint.hpp).
SimulationState get_state(ByteReader& r, std::uint32_t version, bool cuts) {
    SimulationState s;
    ParticleStore& p = s.particles;
    p.id = r.get_array<std::int64_t>("particle ids");
    for (auto* field : {&p.position, &p.velocity, &p.angular_velocity, &p.force, &p.torque})
        *field = r.get_array<Vec3>("particle vectors");
    for (auto* field : {&p.radius, &p.inv_mass, &p.inv_inertia, &p.mass}) *field = r.get_array<double>("particle scalars");
    for (auto* field : {&p.material, &p.motion, &p.tag}) *field = r.get_array<std::int32_t>("particle indices");
    p.reference_position = r.get_array<Vec3>("reference positions");
    p.image_shift = r.get_array<Vec3>("image shifts");
    p.half_kick.assign(p.id.size(), Vec3{});  // not kept: 0 between steps
    s.neighbors.pairs.first = r.get_array<std::uint32_t>("neighbour pairs");
    s.neighbors.pairs.second = r.get_array<std::uint32_t>("neighbour pairs");
    s.neighbors.pairs.image = r.get_array<std::uint8_t>("neighbour pair images");
    s.neighbors.pairs.set_histories(get_histories(r, version, "contact history"));
    s.neighbors.position_at_build = r.get_array<Vec3>("positions at the last neighbour build");
    s.neighbors.builds = r.get<std::int64_t>("neighbour builds");
    s.wall_history = get_histories(r, version, "wall contact history");
    if (version >= 8)
        s.wall_feature = r.get_array<std::uint32_t>("wall contact features");
    else  // before: no meshes, no features
        s.wall_feature.assign(s.wall_history.size(), 0);
    s.motions = r.get_array<MotionClock>("motions");
    if (version >= 9) s.inserted = r.get_array<std::int64_t>("spheres poured in");
    s.dt = r.get<double>("dt");
    s.time = r.get<double>("time");
    s.step = r.get<std::int64_t>("step");
    s.owned = p.id.size();  // formats 2 and 3: one rank, every sphere its own
    if (version >= 4) {
        s.owned = static_cast<std::size_t>(r.get<std::uint64_t>("own spheres"));
        if (cuts) s.slabs.cuts = r.get_array<double>("slab cuts");
        for (int side = 0; side < 2; ++side) {
            const auto sd = static_cast<std::size_t>(side);
            s.slabs.send[sd] = r.get_array<std::uint32_t>("ghosts sent");
            s.slabs.receive_begin[sd] = static_cast<std::size_t>(r.get<std::uint64_t>("ghosts received"));
            s.slabs.receive_count[sd] = static_cast<std::size_t>(r.get<std::uint64_t>("ghosts received"));
        }
        s.ranks = r.get<std::int32_t>("ranks");
        if (s.ranks < 1) r.fail("ranks: fewer than one");
    }
    return s;
}

// The end of a checkpoint file's name after NNNNNN for a rank.
std::string rank_suffix(CheckpointRank who) {
    return who.ranks > 1 ? ".r" + std::to_string(who.rank) + ".tck" : ".tck";
}

// NNNNNN of a checkpoint file of any kind (NNNNNN.tck, NNNNNN.rR.tck), or -1
// for another file.
long any_checkpoint_number(const fs::path& file) {
    const std::string name = file.filename().string();
    if (name.size() < 10 || !name.ends_with(".tck") || name[6] != '.' ||
        !std::all_of(name.begin(), name.begin() + 6, ::isdigit))
        return -1;
    return std::stol(name.substr(0, 6));
}

// NNNNNN of RUN/checkpoints/NNNNNN.tck (of a rank: NNNNNN.rR.tck), or -1
// for another file.
long checkpoint_number(const fs::path& file, CheckpointRank who) {
    const std::string name = file.filename().string(), suffix = rank_suffix(who);
    return name.size() == 6 + suffix.size() && name.substr(6) == suffix ? any_checkpoint_number(file) : -1;
}

}  // namespace

template <class T>
const T& CheckpointRecord::get(const std::string& key, const char* kind) const {
    const auto found = values_.find(key);
    if (found == values_.end()) throw Error(source + ": record key \"" + key + "\" is missing");
    if (const T* v = std::get_if<T>(&found->second)) return *v;
    throw Error(source + ": record key \"" + key + "\" is not " + kind);
}
template const double& CheckpointRecord::get<double>(const std::string&, const char*) const;
template const std::int64_t& CheckpointRecord::get<std::int64_t>(const std::string&, const char*) const;
template const std::string& CheckpointRecord::get<std::string>(const std::string&, const char*) const;
template const std::vector<double>& CheckpointRecord::get<std::vector<double>>(const std::string&, const char*) const;

// Written in one piece (no copy of the payload: a checkpoint of 10^7 spheres
// is gigabytes), the payload length filled in afterwards.
std::string encode_checkpoint(const Checkpoint& c) {
    ByteWriter w;
    for (char ch : magic) w.put(ch);
    w.put(checkpoint_format_version);
    w.put(std::uint64_t{0});  // the payload length, below
    put_record(w, c.record);
    put_scenario(w, c.scenario);
    put_state(w, c.state);
    std::string bytes = w.take();
    const auto length = static_cast<std::uint64_t>(bytes.size() - header_size);
    std::memcpy(bytes.data() + header_size - sizeof length, &length, sizeof length);
    const std::uint32_t checksum = crc32(bytes);
    bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    return bytes;
}

namespace {
// Checks the header (the first header_size bytes of `head`) against the
// size of the whole file; returns the format version and the payload length.
struct Header {
    std::uint32_t version = 0;
    std::uint64_t length = 0;
};
Header check_header(std::string_view head, std::uint64_t file_size, const std::string& name) {
    ByteReader header(head, name);
    if (head.substr(0, magic.size()) != magic) header.fail("not a tumble checkpoint (no TUMBLECK at the start)");
    for (std::size_t k = 0; k < magic.size(); ++k) header.get<char>("magic");
    const auto version = header.get<std::uint32_t>("format version");
    if (version < 2 || version > checkpoint_format_version)
        header.fail(fmt::format("checkpoint format version {}, this tumble reads versions 2 to {}", version,
                                checkpoint_format_version));
    const auto length = header.get<std::uint64_t>("payload length");
    if (length != file_size - std::min<std::uint64_t>(file_size, header_size + sizeof(std::uint32_t)))
        header.fail(fmt::format("{} bytes, the header announces {} (truncated or damaged)", file_size,
                                header_size + length + sizeof(std::uint32_t)));
    return {version, length};
}
}  // namespace

Checkpoint decode_checkpoint(std::string_view bytes, const std::string& name) {
    const auto [version, length] = check_header(bytes, bytes.size(), name);
    ByteReader header(bytes, name);
    const std::string_view covered = bytes.substr(0, header_size + length);
    ByteReader trailer(bytes.substr(covered.size()), name);
    if (trailer.get<std::uint32_t>("checksum") != crc32(covered)) header.fail("checksum mismatch (damaged)");

    ByteReader r(bytes.substr(header_size, length), name);
    Checkpoint c;
    c.record = get_record(r);
    c.record.source = name;
    c.scenario = get_scenario(r, version);
    const ByteReader at_state = r;
    try {
        c.state = get_state(r, version, version >= 4);
        if (!r.at_end()) r.fail("bytes left over after the state (damaged)");
    } catch (const Error&) {
        if (version != 4) throw;
        r = at_state;  // format 4 without the cuts (checkpoint.hpp)
        c.state = get_state(r, version, false);
        if (!r.at_end()) r.fail("bytes left over after the state (damaged)");
    }
    return c;
}

std::vector<fs::path> checkpoint_files(const fs::path& run_directory, CheckpointRank who) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(run_directory / "checkpoints", ec))
        if (checkpoint_number(entry.path(), who) >= 0) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

long next_checkpoint_number(const fs::path& run_directory) {
    long newest = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(run_directory / "checkpoints", ec))
        newest = std::max(newest, any_checkpoint_number(entry.path()));
    return newest + 1;
}

fs::path write_checkpoint(const fs::path& run_directory, const Checkpoint& checkpoint, CheckpointRank who,
                          long number) {
    const fs::path folder = run_directory / "checkpoints";
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(folder.string() + ": cannot create the checkpoint folder: " + ec.message());
    std::vector<fs::path> old = checkpoint_files(run_directory, who);
    if (number <= 0) number = next_checkpoint_number(run_directory);
    const fs::path file = folder / fmt::format("{:06d}{}", number, rank_suffix(who));
    write_file_atomically(file, encode_checkpoint(checkpoint));
    old.push_back(file);
    for (std::size_t k = 0; k + 2 < old.size(); ++k) fs::remove(old[k], ec);
    return file;
}

namespace {
// The bytes of a checkpoint file: a regular file of at most max_bytes whose
// header fits its size, checked before the file is read in.
std::string read_checkpoint_file(const fs::path& file, std::uintmax_t max_bytes) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw Error(file.string() + ": not a regular file");
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) throw Error(file.string() + ": cannot read its size: " + ec.message());
    if (size > max_bytes)
        throw Error(fmt::format("{}: {} bytes, more than the {} bytes a checkpoint may have here (the memory limit)",
                                file.string(), size, max_bytes));
    std::ifstream in(file, std::ios::binary);
    std::string head(header_size, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    check_header(head, size, file.string());
    return read_text_file(file, static_cast<std::size_t>(size));
}

// Why the output files are shorter than when the checkpoint was written
// (a power cut loses what was not yet on the disk), or empty.
// The series a checkpoint records the lengths of are written a whole row
// at a time: a length that ends inside a row (a forged record, with its
// checksum made anew) would leave a cut row behind on resume.
bool ends_a_row(const fs::path& file, std::int64_t length) {
    if (length == 0) return true;
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    char last = 0;
    const bool read = ::pread(fd, &last, 1, static_cast<off_t>(length - 1)) == 1;
    ::close(fd);
    return read && last == '\n';
}

std::string recorded_lengths_problem(const CheckpointRecord& record, const fs::path& directory) {
    for (const auto& [key, value] : record.values()) {
        if (key.rfind("file:", 0) != 0) continue;
        const fs::path file = directory / key.substr(5);
        const std::int64_t length = record.integer(key);
        std::error_code ec;
        const auto size = fs::file_size(file, ec);
        if (ec || length < 0 || size < static_cast<std::uintmax_t>(length))
            return file.string() + " is shorter than when the checkpoint was written (" + std::to_string(length) +
                   " bytes)";
        if (!ends_a_row(file, length))
            return "its length of " + file.string() + ", " + std::to_string(length) + " bytes, ends inside a row";
    }
    return {};
}

// The times of the snapshots written before the checkpoint, which the
// .pvd indexes are written from again: finite, in order, none after the
// state's own time.
std::string snapshot_times_problem(const Checkpoint& c) {
    if (!c.record.has("snapshot_times")) return {};
    double previous = -INFINITY;
    for (double t : c.record.numbers("snapshot_times")) {
        if (!(t >= previous && t <= c.state.time))
            return fmt::format("record key \"snapshot_times\" holds {}, not a time in order up to the state's "
                               "time {}", t, c.state.time);
        previous = t;
    }
    return {};
}
}  // namespace

namespace {
// The newest of `files` (oldest first) numbered at most `up_to` that reads
// back intact, its output files at least as long as it recorded, into
// `loaded`; `loaded.rejected` gets why each newer one did not. False if none.
bool load_newest_of(const std::vector<fs::path>& files, const fs::path& run_directory, std::uintmax_t max_bytes,
                    long up_to, LoadedCheckpoint& loaded) {
    for (auto file = files.rbegin(); file != files.rend(); ++file) {
        if (any_checkpoint_number(*file) > up_to) continue;
        try {
            loaded.checkpoint = decode_checkpoint(read_checkpoint_file(*file, max_bytes), file->string());
            if (const std::string why = recorded_lengths_problem(loaded.checkpoint.record, run_directory); !why.empty())
                throw Error(file->string() + ": " + why);
            if (const std::string why = snapshot_times_problem(loaded.checkpoint); !why.empty())
                throw Error(file->string() + ": " + why);
            loaded.file = *file;
            return true;
        } catch (const Error& e) {
            loaded.rejected.push_back(e.what());
        }
    }
    return false;
}

// Why none of a rank's files could be loaded.
std::string no_checkpoint_reason(const fs::path& run_directory, const std::vector<fs::path>& files,
                                 const LoadedCheckpoint& loaded, CheckpointRank who) {
    std::string reason = files.empty() ? "no checkpoints (RUN/checkpoints/NNNNNN" + rank_suffix(who) + ")"
                                       : "no intact checkpoint";
    for (const std::string& why : loaded.rejected) reason += "\n  " + why;
    return run_directory.string() + ": cannot resume: " + reason;
}

// What a rank's checkpoint file says of the moment and the run it belongs
// to, compared among the files of one checkpoint before they are used
// together.
struct RankFile {
    std::string file;  // empty: the rank has none; `problem` says why
    std::string problem;
    std::int64_t step = 0;
    double time = 0.0;
    std::int64_t ranks = 0;
    std::int64_t rank = -1;  // the record's "rank"; -1 in files written before it was kept
    std::uint32_t run = 0;   // the run: a checksum of its command and scenario
};

RankFile rank_file(const Checkpoint& c, const fs::path& file) {
    ByteWriter scenario;
    scenario.put(c.record.has("command") ? c.record.text("command") : std::string());
    put_scenario(scenario, c.scenario);
    return {file.string(),
            {},
            c.state.step,
            c.state.time,
            c.record.has("ranks") ? c.record.integer("ranks") : 1,
            c.record.has("rank") ? c.record.integer("rank") : -1,
            crc32(scenario.take())};
}

std::string encode_rank_file(const RankFile& f) {
    ByteWriter w;
    w.put(f.file);
    w.put(f.problem);
    w.put(f.step);
    w.put(f.time);
    w.put(f.ranks);
    w.put(f.rank);
    w.put(f.run);
    return w.take();
}

RankFile decode_rank_file(std::string_view bytes) {
    ByteReader r(bytes, "a rank's checkpoint summary");
    RankFile f;
    f.file = r.get_string("file");
    f.problem = r.get_string("problem");
    f.step = r.get<std::int64_t>("step");
    f.time = r.get<double>("time");
    f.ranks = r.get<std::int64_t>("ranks");
    f.rank = r.get<std::int64_t>("rank");
    f.run = r.get<std::uint32_t>("run");
    return f;
}

// Why rank `rank`'s file `f` does not belong with rank 0's `first` (the
// same moment of the same run on as many ranks), or empty.
std::string rank_file_mismatch(const RankFile& f, std::int64_t rank, const RankFile& first) {
    const std::string first_name = fs::path(first.file).filename().string();
    if (f.run != first.run)
        return fmt::format("{}: rank 0's {} is of another run (another command or scenario): the ranks' files are of "
                           "different runs", f.file, first_name);
    if (f.step != first.step || f.time != first.time)
        return fmt::format("{}: step {} (time {:.9g} s), rank 0's {} step {} (time {:.9g} s): the ranks' files are of "
                           "different moments", f.file, f.step, f.time, first_name, first.step, first.time);
    if (f.ranks != first.ranks)
        return fmt::format("{}: record key \"ranks\" is {}, rank 0's {} {}: the ranks' files are of runs on "
                           "different numbers of ranks", f.file, f.ranks, first_name, first.ranks);
    if (f.rank >= 0 && f.rank != rank)
        return fmt::format("{}: record key \"rank\" is {}: written by rank {}, not rank {} (a renamed file)", f.file,
                           f.rank, f.rank, rank);
    return {};
}
}  // namespace

LoadedCheckpoint load_newest_checkpoint(const fs::path& run_directory, std::uintmax_t max_bytes, CheckpointRank who) {
    LoadedCheckpoint loaded;
    const std::vector<fs::path> files = checkpoint_files(run_directory, who);
    if (load_newest_of(files, run_directory, max_bytes, std::numeric_limits<long>::max(), loaded)) return loaded;
    throw Error(no_checkpoint_reason(run_directory, files, loaded, who));
}

LoadedCheckpoint load_shared_checkpoint(const fs::path& run_directory, std::uintmax_t max_bytes, CheckpointRank who) {
    LoadedCheckpoint loaded;
    const std::vector<fs::path> files = checkpoint_files(run_directory, who);
    bool have = load_newest_of(files, run_directory, max_bytes, std::numeric_limits<long>::max(), loaded);
    // The ranks agree on one number: the newest that every rank holds intact.
    // A rank whose newest is newer than another's goes back to that one; each
    // round lowers the highest number, and every rank makes the same rounds.
    for (;;) {
        const double mine = have ? static_cast<double>(any_checkpoint_number(loaded.file)) : -1.0;
        const double lowest = -mpi::max(-mine), highest = mpi::max(mine);
        if (lowest == highest || lowest < 0) break;
        if (mine > lowest) {
            loaded.rejected.push_back(loaded.file.string() + ": not every rank has an intact checkpoint of this number");
            have = load_newest_of(files, run_directory, max_bytes, static_cast<long>(lowest), loaded);
        }
    }
    // Then every rank has every rank's account of its file (each sends its
    // own round the ring), so that all find the same verdict and stop alike.
    RankFile mine = have ? rank_file(loaded.checkpoint, loaded.file) : RankFile{};
    if (!have) mine.problem = no_checkpoint_reason(run_directory, files, loaded, who);
    const std::string own = encode_rank_file(mine);
    std::vector<RankFile> all(static_cast<std::size_t>(who.ranks));
    all[static_cast<std::size_t>(who.rank)] = mine;
    for (int k = 1; k < who.ranks; ++k) {
        const int from = (who.rank - k + who.ranks) % who.ranks;
        const mpi::Bytes in = mpi::exchange((who.rank + k) % who.ranks, mpi::Bytes(own.begin(), own.end()), from,
                                            checkpoint_agreement_tag);
        all[static_cast<std::size_t>(from)] = decode_rank_file(std::string_view(in.data(), in.size()));
    }
    for (std::size_t r = 0; r < all.size(); ++r)
        if (all[r].file.empty()) throw Error(fmt::format("rank {}: {}", r, all[r].problem));
    for (std::size_t r = 1; r < all.size(); ++r)
        if (const std::string why = rank_file_mismatch(all[r], static_cast<std::int64_t>(r), all[0]); !why.empty())
            throw Error(why + "; resume is not possible from them (restore every rank's file of one checkpoint)");
    return loaded;
}

LoadedCheckpoint load_whole_checkpoint(const fs::path& run_directory, std::uintmax_t max_bytes) {
    LoadedCheckpoint first = load_newest_checkpoint(run_directory, max_bytes, {0, 2});
    const std::int64_t ranks = first.checkpoint.record.integer("ranks");
    const std::string number = first.file.filename().string().substr(0, 6);
    if (ranks < 2 || ranks > 1'000'000)
        throw Error(first.file.string() + ": record key \"ranks\" is " + std::to_string(ranks) +
                    ", not the rank count of a run on several ranks");
    const RankFile first_file = rank_file(first.checkpoint, first.file);
    std::vector<SimulationState> parts{std::move(first.checkpoint.state)};
    for (std::int64_t r = 1; r < ranks; ++r) {
        const fs::path file = run_directory / "checkpoints" / (number + ".r" + std::to_string(r) + ".tck");
        Checkpoint part = decode_checkpoint(read_checkpoint_file(file, max_bytes), file.string());
        if (const std::string why = rank_file_mismatch(rank_file(part, file), r, first_file); !why.empty())
            throw Error(why + "; cannot resume from them");
        parts.push_back(std::move(part.state));
    }
    first.checkpoint.state = whole_state(parts);
    first.checkpoint.record.set("ranks", std::int64_t{1});  // a whole state now, for any number of ranks
    return first;
}

CheckpointRank newest_checkpoint_kind(const fs::path& run_directory, std::uintmax_t max_bytes) {
    const CheckpointRank one{}, ranks{0, 2};
    if (checkpoint_files(run_directory, ranks).empty()) return one;
    if (checkpoint_files(run_directory, one).empty()) return ranks;
    const auto newest_step = [&](CheckpointRank who) -> std::int64_t {
        try {
            return load_newest_checkpoint(run_directory, max_bytes, who).checkpoint.state.step;
        } catch (const Error&) {
            return -1;  // none of this kind reads back: the other kind's, or the error it gives
        }
    };
    return newest_step(ranks) > newest_step(one) ? ranks : one;
}

bool resumable(const fs::path& run_directory, std::uintmax_t max_bytes) {
    try {
        return load_newest_checkpoint(run_directory, max_bytes, newest_checkpoint_kind(run_directory, max_bytes))
                   .checkpoint.record.integer("finished") == 0;
    } catch (const Error&) {
        return false;
    }
}

void record_file_lengths(CheckpointRecord& record, const fs::path& directory, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const fs::path file = directory / name;
        std::error_code ec;
        const auto size = fs::file_size(file, ec);
        if (ec) continue;
        // On the disk before the checkpoint that counts on it.
        const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0 || ::fsync(fd) != 0) {
            const std::string why = std::strerror(errno);
            if (fd >= 0) ::close(fd);
            throw Error(file.string() + ": flushing to disk failed: " + why);
        }
        ::close(fd);
        record.set(std::string("file:") + name, static_cast<std::int64_t>(size));
    }
}

void truncate_to_recorded_lengths(const CheckpointRecord& record, const fs::path& directory) {
    if (const std::string why = recorded_lengths_problem(record, directory); !why.empty())
        throw Error(why + "; cannot resume");
    for (const auto& [key, value] : record.values()) {
        if (key.rfind("file:", 0) != 0) continue;
        const fs::path file = directory / key.substr(5);
        const std::int64_t length = record.integer(key);
        std::error_code ec;
        fs::resize_file(file, static_cast<std::uintmax_t>(length), ec);
        if (ec) throw Error(file.string() + ": cannot cut back to " + std::to_string(length) + " bytes: " + ec.message());
    }
}

}  // namespace tumble::io
