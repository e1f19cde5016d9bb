// SPDX-License-Identifier: MIT
// The paper's experiment as a protocol (docs/DRUM.md): build the
// particle-walled drum, fill it, let the bed settle with the drum at rest,
// turn it for the asked number of revolutions while sampling <z> per
// component, photograph the grains, then analyse. Checkpoints on the way
// let resume_drum() continue an interrupted run (docs/CHECKPOINTS.md).
#include "experiments/drum.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "experiments/drum_setup.hpp"
#include "experiments/limits.hpp"
#include "experiments/machine.hpp"
#include "experiments/progress.hpp"
#include "io/band_output.hpp"
#include "io/drum_output.hpp"
#include "io/output.hpp"
#include "io/run_lock.hpp"
#include "io/snapshots.hpp"
#include "io/step_times.hpp"
#include "tumble/analysis/bands.hpp"
#include "tumble/analysis/drum_measure.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/isa.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/sim/particle_setup.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::experiments {

namespace fs = std::filesystem;

namespace {

// The two components, counted in every sphere of the drum (`p`): in the
// two-component mode named by their materials (the paper's: material-1,
// material-2), in the self mode by the half they start in.
std::vector<io::DrumComponent> components_of(const ParticleStore& p, const std::string& mode,
                                             const DrumMaterials& materials) {
    std::vector<io::DrumComponent> out(2);
    const bool self = mode == "self";
    out[0] = {self ? "left" : materials.materials.at(materials.large).name, 0, 0.0, -1.0};
    out[1] = {self ? "right" : materials.materials.at(materials.small).name, 0, 0.0, +1.0};
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        io::DrumComponent& c = out.at(static_cast<std::size_t>(p.tag[i]));
        ++c.grains;
        c.mass += p.mass[i];
    }
    return out;
}

// Band samples (band_profile.csv) per revolution, at most: 4 keep the file
// of a 500-revolution drum of 160 bins to about 9 MB (docs/BAND-ANALYSIS.md), and
// resolve bands that live for tens of revolutions.
constexpr int band_samples_per_revolution = 4;

// What a drum run carries from one process to the next, besides the engine
// state (kept in its checkpoints).
struct DrumPlan {
    io::DrumRunInfo info;
    int snapshots_per_revolution = 0;
    double settle_speed = 0.0;     // m/s
    double settle_max_time = 0.0;  // s
    double fall_time = 0.0;        // s: settle at least this long
    double checkpoint_revolutions = 0.0;
    bool plot = true;
    bool quiet = false;
    ProgressStyle progress;  // of this process: not kept in checkpoints
    bool rotating = false;
    std::int64_t rotation_start_step = 0;
};

void save_plan(io::CheckpointRecord& r, const DrumPlan& plan) {
    r.set("command", std::string("drum"));
    r.set("drum.run_info", io::drum_run_info_text(plan.info));
    r.set("drum.snapshots_per_revolution", std::int64_t{plan.snapshots_per_revolution});
    r.set("drum.settle_speed", plan.settle_speed);
    r.set("drum.settle_max_time", plan.settle_max_time);
    r.set("drum.fall_time", plan.fall_time);
    r.set("drum.checkpoint_revolutions", plan.checkpoint_revolutions);
    r.set("drum.plot", std::int64_t{plan.plot});
    r.set("drum.rotating", std::int64_t{plan.rotating});
    r.set("drum.rotation_start_step", plan.rotation_start_step);
}

DrumPlan load_plan(const io::CheckpointRecord& r) {
    DrumPlan plan;
    plan.info = io::parse_drum_run_info(r.text("drum.run_info"), r.source + " (drum.run_info)");
    plan.snapshots_per_revolution = static_cast<int>(r.integer("drum.snapshots_per_revolution"));
    plan.settle_speed = r.number("drum.settle_speed");
    plan.settle_max_time = r.number("drum.settle_max_time");
    plan.fall_time = r.number("drum.fall_time");
    plan.checkpoint_revolutions = r.number("drum.checkpoint_revolutions");
    plan.plot = r.integer("drum.plot") != 0;
    plan.rotating = r.integer("drum.rotating") != 0;
    plan.rotation_start_step = r.integer("drum.rotation_start_step");
    return plan;
}

// The drum's scenario domain is the drum with a margin of one wall sphere: a
// grain centre outside it has passed through the wall.
HealthLimits drum_limits(const Scenario& s) {
    HealthLimits limits = default_health_limits(s);
    limits.bounded = {true, true, !s.domain.periodic[2]};  // a periodic axis wraps the grains
    limits.lo = s.domain.lo;
    limits.hi = s.domain.hi;
    limits.region = "the drum";
    return limits;
}

// Settling and rotation from wherever `sim` stands, then the analysis.
class DrumLoop {
public:
    // fields: taken during the run, kept in its checkpoints, written at its end.
    DrumLoop(Simulation& sim, DrumPlan plan, fs::path dir, CheckpointPolicy policy, bool continuing,
             DrumSampleHook on_sample, FieldRecorder* fields = nullptr)
        : sim_(sim), plan_(std::move(plan)), dir_(std::move(dir)), on_sample_(std::move(on_sample)), fields_(fields),
          period_(2.0 * pi / plan_.info.omega),
          steps_(std::llround(plan_.info.revolutions * period_ / sim.dt())),
          sample_every_(std::max<std::int64_t>(1, std::llround(period_ / plan_.info.samples_per_revolution / sim.dt()))),
          snapshot_every_(plan_.snapshots_per_revolution > 0
                              ? std::max<std::int64_t>(1, std::llround(period_ / plan_.snapshots_per_revolution / sim.dt()))
                              : 0),
          band_every_(sample_every_ * ((plan_.info.samples_per_revolution + band_samples_per_revolution - 1) /
                                       band_samples_per_revolution)),
          frame_{plan_.info.inner_length, plan_.info.inner_radius, 2, plan_.info.profile_bins, plan_.info.omega},
          band_frame_{plan_.info.inner_length, plan_.info.band_bins, 1},
          checkpoints_(dir_, with_revolutions(policy), drum_limits(sim.scenario())) {
        if (!writer()) {
            plan_.progress = progress_style(true, 0.0);
            return;
        }
        series_.emplace(dir_ / "time_series.csv", sim.scenario(), continuing);
        if (continuing && plan_.rotating) drum_series_.emplace(dir_, plan_.info, true);
        if (continuing && plan_.rotating && plan_.info.band_bins > 0) band_profile_.emplace(dir_, plan_.info.band_bins, true);
        band_field_.inner_length = plan_.info.inner_length;
        band_field_.periodic = plan_.info.periodic_axis;
        if (band_profile_ && continuing && plan_.info.until_band_change > 0.0)  // the samples before the stop
            band_field_ = io::read_band_profile(dir_ / "band_profile.csv", plan_.info).field;
    }

    // snapshot_times: of the snapshots written before a resume.
    DrumOutcome run(const std::vector<double>& snapshot_times) {
        return {protocol(snapshot_times), plan_.plot, dir_};
    }

private:
    int protocol(const std::vector<double>& snapshot_times) {
        if (plan_.rotating && snapshot_every_) snapshots_.emplace(dir_, snapshot_times, !sim_.scenario().walls.empty());
        if (!plan_.rotating) {
            if (settle() == Checkpointer::Due::and_stop) return checkpoints_.stopped(sim_.step_count());
            start_rotation();
        }
        if (rotate() == Checkpointer::Due::and_stop) return checkpoints_.stopped(sim_.step_count());
        return finish();
    }

    // Shared among MPI ranks, rank 0 alone talks, measures and writes; the
    // others step and join the collective calls (the gathering of the
    // spheres, observe(), the snapshots, the checkpoints).
    bool talk() const { return !plan_.quiet && writer(); }
    static bool writer() { return mpi::rank() == 0; }

    // Every sphere, for a measurement: on one rank the simulation's; shared
    // among ranks gathered on rank 0 (collective; empty elsewhere).
    const ParticleStore& all_spheres() {
        if (!sim_.shared()) return sim_.particles();
        gathered_ = sim_.gathered();
        return gathered_;
    }

    CheckpointPolicy with_revolutions(CheckpointPolicy policy) const {
        const double steps = plan_.checkpoint_revolutions * period_ / sim_.dt();
        policy.every_steps = steps > 0.0 ? std::max<std::int64_t>(1, std::llround(steps)) : 0;
        return policy;
    }

    // Settle with the drum at rest: at least fall_time, until the rms grain
    // speed is below settle_speed, at most settle_max_time. Its progress is
    // the simulated time and the rms speed against their criteria: the bed
    // usually settles long before the maximum time.
    Checkpointer::Due settle() {
        const std::int64_t check_every = std::max<std::int64_t>(1, std::llround(1e-3 / sim_.dt()));
        Progress progress("settling", sim_.step_count(), 0, plan_.progress,
                          {.particles = sim_.scenario().free_count()});
        while (sim_.time() < plan_.settle_max_time) {
            advance(check_every);
            const double speed = rms_grain_speed(sim_);
            progress.update(sim_.step_count(),
                            fmt::format("t = {:.3f} s ({:.3g} to {:.3g} s), rms grain speed {:.2g} m/s, "
                                        "settled below {:.2g}",
                                        sim_.time(), plan_.fall_time, plan_.settle_max_time, speed,
                                        plan_.settle_speed));
            if (sim_.time() >= plan_.fall_time && speed < plan_.settle_speed) {
                plan_.info.settled = true;
                break;
            }
            const auto due = checkpoints_.after_steps(sim_, 0);
            if (due != Checkpointer::Due::no) checkpoint(false, 0.0);
            if (due == Checkpointer::Due::and_stop) {
                progress.finish();
                return due;
            }
        }
        progress.finish();
        return Checkpointer::Due::no;
    }

    // Revolution N = 0 is the start of rotation.
    void start_rotation() {
        io::DrumRunInfo& info = plan_.info;
        info.settle_time = sim_.time();
        const ParticleStore& all = all_spheres();
        if (writer()) info.fill_fraction = analysis::measure_drum(all, frame_).fill_fraction;
        const double speed = rms_grain_speed(sim_);
        if (talk())
            fmt::print("{} after {:.3g} s: rms grain speed {:.3g} m/s; fill fraction {:.3f}, solid fraction {:.3f}\n",
                       info.settled ? "settled" : "warning: NOT settled", info.settle_time, speed,
                       info.fill_fraction, info.solid_fraction);
        sim_.set_motion(0, drum_rotation(drum_angular_velocity(info.omega, info.spin_up_time, 0.0)));
        plan_.rotating = true;
        plan_.rotation_start_step = sim_.step_count();
        if (writer()) {
            io::write_drum_run_info(dir_ / "drum_run.toml", info);
            drum_series_.emplace(dir_, info);
            if (info.band_bins > 0) band_profile_.emplace(dir_, info.band_bins);
        }
        if (snapshot_every_) snapshots_.emplace(dir_, std::vector<double>{}, !sim_.scenario().walls.empty());
        if (talk()) {
            fmt::print("rotating at {:.4g} rad/s (Froude {:.3g}) for {} revolutions: {} steps, {} samples per revolution\n",
                       info.omega, info.froude, info.revolutions, steps_, info.samples_per_revolution);
            if (info.revolutions < 10.0)
                fmt::print("note: {} revolutions is a short run (the default is reduced so that it takes minutes); the "
                           "paper's runs span tens of revolutions: --revolutions N\n",
                           info.revolutions);
        }
        sample();
        if (snapshot_every_) snapshots_->write(sim_);
    }

    // Rotation step k = 1 .. steps_. The steps between two events (a sample, a
    // snapshot, a checkpoint by steps, the stop step, the spin-up's settings)
    // run as one Simulation::advance(), one parallel region, which gives the
    // same bytes as single steps; the clock, signals and health are looked at
    // after at most `batch` steps.
    Checkpointer::Due rotate() {
        constexpr std::int64_t batch = 100;
        const std::int64_t done = sim_.step_count() - plan_.rotation_start_step;  // > 0 after a resume
        Progress progress("rotation", done, steps_, plan_.progress,
                          {.particles = sim_.scenario().free_count(), .steps_per_revolution = period_ / sim_.dt()});
        sim_.reset_step_times();  // the rotation's (the settling's are not told)
        for (std::int64_t k = done; k < steps_;) {
            std::int64_t next = std::min(steps_, (k / batch + 1) * batch);
            const auto at_multiple = [&](std::int64_t every) {
                if (every > 0) next = std::min(next, (k / every + 1) * every);
            };
            at_multiple(sample_every_);
            at_multiple(snapshot_every_);
            at_multiple(checkpoints_.policy().every_steps);
            if (const std::int64_t stop = checkpoints_.policy().stop_at_step; stop > sim_.step_count())
                next = std::min(next, k + stop - sim_.step_count());
            if (spin_up(k + 1)) next = k + 1;  // the ramp sets the speed before every step
            advance(next - k);
            k = next;
            if (k % sample_every_ == 0) sample();
            if (snapshot_every_ && k % snapshot_every_ == 0) snapshots_->write(sim_);
            progress.update(k);
            if (ends_on_band_change(k)) {
                steps_ = k;
                break;
            }
            const auto due = checkpoints_.after_steps(sim_, k);
            if (due != Checkpointer::Due::no) checkpoint(false, progress.elapsed_seconds());
            if (due == Checkpointer::Due::and_stop) {
                progress.finish();
                return due;
            }
        }
        progress.finish();
        plan_.info.wall_seconds += progress.elapsed_seconds();
        rotation_times_ =
            io::step_times_spread(sim_.step_times(), progress.elapsed_seconds(), sim_.threads(), sim_.shared());
        return Checkpointer::Due::no;
    }

    void advance(std::int64_t steps) {
        if (fields_) fields_->advance(sim_, steps);
        else sim_.advance(steps);
    }

    // The spin-up ramp (spin_up_setting in setup/drum.hpp): sets the speed
    // before step k if the ramp has one for it, and says whether it had.
    bool spin_up(std::int64_t k) {
        const double omega = spin_up_setting(plan_.info.omega, plan_.info.spin_up_time, sim_.dt(), k);
        if (omega < 0.0) return false;
        sim_.set_motion(0, drum_rotation(omega));
        return true;
    }

    void sample() {
        const double start = static_cast<double>(plan_.rotation_start_step) * sim_.dt();
        const double revolutions = plan_.info.omega * (sim_.time() - start) / (2.0 * pi);
        const ParticleStore& all = all_spheres();
        const Observables observed = sim_.observe();  // collective
        if (!writer()) return;
        const analysis::DrumState state = analysis::measure_drum(all, frame_);
        drum_series_->write(revolutions, sim_.time(), state);
        // The band profile at every band_every_-th step of the rotation and at its end.
        const std::int64_t k = sim_.step_count() - plan_.rotation_start_step;
        if (band_profile_ && (k % band_every_ == 0 || k == steps_)) {
            const analysis::BandSample bands = analysis::measure_bands(all, band_frame_);
            band_profile_->write(revolutions, bands);
            if (plan_.info.until_band_change > 0.0) watch_band_count(revolutions, bands);
        }
        series_->write(observed);
        if (on_sample_) on_sample_({revolutions, state, sim_});
    }

    // --until-band-change: the band count of every band sample so far, as
    // the run's analysis will count it; once it has differed from the
    // start's for the revolutions asked, the run is marked to end.
    void watch_band_count(double revolutions, const analysis::BandSample& bands) {
        band_field_.revolutions.push_back(revolutions);
        band_field_.small_fraction.push_back(bands.small_fraction);
        band_field_.grains.push_back(bands.grains);
        band_field_.small_grains.push_back(bands.small_grains);
        const analysis::BandHistory h = analysis::analyze_band_field(band_field_);
        const double since = analysis::band_count_changed(h, plan_.info.until_band_change);
        if (!std::isfinite(since)) return;
        io::DrumRunInfo& info = plan_.info;
        info.band_change_since = since;
        info.bands_at_start = static_cast<int>(h.samples.front().bands.size());
        info.bands_at_end = static_cast<int>(h.samples.back().bands.size());
        if (talk())
            fmt::print("the band count left its start value, {}, at N = {:.4g} and has not come back for {:.3g} "
                       "revolutions ({} bands now): the rotation ends at N = {:.4g} (--until-band-change)\n",
                       info.bands_at_start, since, revolutions - since, info.bands_at_end, revolutions);
    }

    // Whether the rotation ends at step k on its band count: decided by rank
    // 0, which measures the bands, and told to every rank at each band sample.
    bool ends_on_band_change(std::int64_t k) const {
        if (!(plan_.info.until_band_change > 0.0) || k % band_every_ != 0) return false;
        const bool ends = plan_.info.band_change_since >= 0.0;
        return sim_.shared() ? mpi::any(ends) : ends;
    }

    int finish() {
        io::DrumRunInfo& info = plan_.info;
        // The run is finished only when its results are written: a checkpoint
        // of the final state first (a resume from it writes the results
        // again), then the results, then the checkpoint that says "finished".
        checkpoint(false, 0.0);
        if (steps_ % sample_every_ != 0) sample();  // always end with the final state
        const double updates = static_cast<double>(sim_.scenario().free_count()) * static_cast<double>(steps_);
        info.grain_updates_per_second = info.wall_seconds > 0.0 ? updates / info.wall_seconds : 0.0;
        std::string summary;
        if (writer()) {
            io::write_drum_run_info(dir_ / "drum_run.toml", info);
            if (talk()) {
                fmt::print("rotation simulated in {:.1f} s: {:.3g} grain updates/s ({:.1f} s per revolution)\n",
                           info.wall_seconds, info.grain_updates_per_second, info.wall_seconds / info.revolutions);
                if (rotation_times_)
                    fmt::print("{}", io::step_times_text(*rotation_times_,
                                                         "the rotation (this process: since its start or resume)"));
                fmt::print("\n");
            }
            summary = io::analyze_drum_run(dir_);
        }
        if (fields_) {
            const std::string written = fields_->write(dir_);
            if (talk()) fmt::print("{}\n", written);
        }
        checkpoint(true, 0.0);
        if (talk()) fmt::print("{}\nwritten to {}\n", summary, dir_.string());
        return 0;
    }

    // seconds: of rotation spent by this process so far.
    void checkpoint(bool finished, double seconds) {
        io::Checkpoint c = checkpoint_of(sim_);
        DrumPlan now = plan_;
        now.info.wall_seconds += seconds;
        save_plan(c.record, now);
        save_policy(c.record, checkpoints_.policy());
        c.record.set("finished", std::int64_t{finished});
        c.record.set("snapshot_times", snapshots_ ? snapshots_->times() : std::vector<double>{});
        if (fields_) fields_->save(c.record);
        if (writer())
            io::record_file_lengths(c.record, dir_,
                                    {"time_series.csv", "drum_series.csv", "profiles.csv", "band_profile.csv"});
        checkpoints_.write(sim_, c);
    }

    Simulation& sim_;
    DrumPlan plan_;
    fs::path dir_;
    DrumSampleHook on_sample_;
    FieldRecorder* fields_;
    double period_;  // s per revolution
    std::int64_t steps_, sample_every_, snapshot_every_, band_every_;
    analysis::DrumFrame frame_;
    analysis::BandFrame band_frame_;
    Checkpointer checkpoints_;
    ParticleStore gathered_;                      // shared among ranks: the spheres of the last measurement
    std::optional<io::TimeSeriesWriter> series_;  // rank 0's, as the next two
    std::optional<io::DrumSeriesWriter> drum_series_;
    std::optional<io::BandProfileWriter> band_profile_;
    analysis::BandField band_field_;  // rank 0's band samples, kept with --until-band-change
    std::optional<io::SnapshotSeries> snapshots_;
    std::optional<io::StepTimesSpread> rotation_times_;  // where this process's rotation spent its time
};

// tumble resume --revolutions: the run's new length.
// done: the rotation's steps so far.
void lengthen(DrumPlan& plan, double revolutions, std::int64_t done, double dt, const fs::path& dir, bool quiet) {
    io::DrumRunInfo& info = plan.info;
    const double period = 2.0 * pi / info.omega;  // s
    step_count(revolutions * period, dt, "--revolutions");  // a length in steps that a run can finish, first
    if (std::llround(revolutions * period / dt) <= done)  // the rotation's length in steps, as DrumLoop counts it
        throw Error(fmt::format("--revolutions {}: the run in {} has turned {:.4g} revolutions already; ask for more",
                                revolutions, dir.string(), static_cast<double>(done) * dt / period));
    const bool talk = !quiet && mpi::rank() == 0;
    if (talk && revolutions != info.revolutions)
        fmt::print("tumble resume: the run's length goes from {} to {} revolutions\n", info.revolutions, revolutions);
    info.revolutions = revolutions;
    if (info.until_band_change > 0.0 && info.band_change_since >= 0.0) {
        if (talk)
            fmt::print("tumble resume: the rotation ended on its band change (N = {:.4g}); it goes on without "
                       "--until-band-change\n",
                       info.band_change_since);
        info.until_band_change = 0.0;
    }
}

// A finished run lengthened is unfinished again: its summary (what marks a
// finished run for tumble sweep, the band study's scripts and a reader)
// goes until the new end writes it anew.
void remove_summary(const fs::path& dir) {
    if (mpi::rank() != 0) return;
    for (const char* name : {"summary.json", "summary.txt"}) {
        std::error_code ec;
        fs::remove(dir / name, ec);
        if (ec) throw Error((dir / name).string() + ": cannot remove the old summary: " + ec.message());
    }
}

}  // namespace

DrumOutcome run_drum(const DrumRunOptions& options) {
    io::DrumSettings s = options.settings;
    const double omega = s.omega();
    const double inner_radius = 0.5 * s.geometry.diameter;
    if (omega * omega * inner_radius / 9.81 > 1.0 && !options.quiet)
        fmt::print("note: Froude number {:.3g} > 1: above the critical speed the grains are held against the wall\n",
                   omega * omega * inner_radius / 9.81);

    const int threads = resolve_threads(options.threads);
    check_memory(drum_memory(s.geometry, static_cast<double>(s.grain_count()), threads, s.skin),
                 memory_limit_bytes(options.max_memory_gib), "command line",  // what the machine cannot do, first
                 "--max-memory GIB");
    check_drum_size(s.geometry, static_cast<double>(s.grain_count()), options.large_drum, "command line");
    DrumSetup setup = build_drum(s, options.allow_unsafe_dt);
    Simulation sim(std::move(setup.scenario), threads, mpi::size() > 1 ? Ranks::world : Ranks::one);
    check_drum_durations(s.revolutions, omega, s.samples_per_revolution, s.settle_max_time, sim.dt());
    std::optional<FieldRecorder> fields;
    if (!options.fields.empty()) fields.emplace(options.fields, sim, 0, options.max_memory_gib, true);

    DrumPlan plan;
    io::DrumRunInfo& info = plan.info;
    info.mode = s.mode;
    info.omega = omega;
    info.froude = omega * omega * setup.wall.inner_radius / 9.81;
    info.revolutions = s.revolutions;
    info.seed = s.seed;
    info.wall_particles = setup.wall.particles.size();
    info.walls = keyword_of(drum_wall_kinds, s.geometry.walls);
    info.mesh = s.mesh.string();
    info.mesh_scale = s.mesh_scale;
    info.materials = sim.scenario().materials;  // (setup.scenario has moved into sim)
    info.paper_materials = s.materials.paper;
    {
        const DrumMaterials& m = s.materials;
        auto name = [&](std::int32_t k) { return k >= 0 ? m.materials.at(k).name : std::string(); };
        info.large_material = name(m.large);
        info.small_material = name(m.small);
        info.wall_material = name(m.wall);
        info.cap_material = s.fill.cap_friction ? std::string(drum_cap_material_name) : name(m.cap >= 0 ? m.cap : m.wall);
    }
    info.inner_radius = setup.wall.inner_radius;
    info.inner_length = setup.wall.inner_length;
    info.periodic_axis = s.geometry.periodic_axis;
    info.spin_up_time = s.spin_up_time;
    info.arrangement = keyword_of(arrangements, s.fill.arrangement);
    info.band_edges = band_edges(s.geometry, s.fill);
    info.cap_friction = s.fill.cap_friction.value_or(-1.0);
    info.until_band_change = s.until_band_change;
    info.dt = sim.dt();
    info.skin = sim.neighbors().skin();
    info.threads = sim.threads();
    info.isa = isa_description();
    info.shear_model = keyword_of(shear_models, s.shear);
    info.friction_normal = keyword_of(friction_normals, s.friction_normal);
    info.tangential_stiffness = keyword_of(tangential_stiffnesses, s.tangential_stiffness);
    info.surface_energy = s.uniform_surface_energy().value_or(-1.0);
    info.samples_per_revolution = s.samples_per_revolution;
    info.profile_bins = s.profile_bins;
    info.band_bins = s.band_bins > 0 ? s.band_bins : analysis::default_band_bins(info.inner_length);
    const ParticleStore all = make_particle_store(sim.scenario());  // every sphere as it starts (on every rank)
    info.components = components_of(all, s.mode, s.materials);
    double grain_volume = 0.0;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (!all.is_kinematic(i)) grain_volume += 4.0 / 3.0 * pi * std::pow(all.radius[i], 3);
    info.solid_fraction = grain_volume / (pi * info.inner_radius * info.inner_radius * info.inner_length);
    plan.snapshots_per_revolution = s.snapshots_per_revolution;
    plan.settle_speed = s.settle_speed;
    plan.settle_max_time = s.settle_max_time;
    plan.fall_time = drum_fall_time(s);
    plan.checkpoint_revolutions = options.checkpoint_revolutions;
    plan.plot = options.plot;
    plan.quiet = options.quiet;
    plan.progress = progress_style(options.quiet, options.progress_every);

    std::optional<io::RunLock> lock;  // rank 0's: the other ranks write only their checkpoints
    if (mpi::rank() == 0) lock.emplace(io::prepare_output_directory(s.output, options.force));
    if (!options.quiet && mpi::rank() == 0) {
        fmt::print("tumble drum: {} mode, {} grains ({} {}, {} {}), {}, inner radius {:.4g} m, "
                   "length {:.4g} m{}; dt = {:.3g} s; instruction set {}\n",
                   s.mode, sim.scenario().free_count(), info.components[0].grains, info.components[0].name,
                   info.components[1].grains, info.components[1].name,
                   s.geometry.walls == DrumWalls::particles
                       ? fmt::format("{} wall particles", info.wall_particles)
                       : std::string(s.geometry.walls == DrumWalls::smooth ? "smooth walls"
                                                                           : "a mantle of triangles and smooth caps"),
                   info.inner_radius, info.inner_length, s.geometry.periodic_axis ? " (periodic axis)" : "", sim.dt(),
                   info.isa);
        if (!s.materials.paper)
            fmt::print("materials: large grains {}{}, wall {}, caps {}\n", info.large_material,
                       s.mode == "self" ? std::string() : ", small grains " + info.small_material, info.wall_material,
                       s.geometry.periodic_axis ? std::string("none") : info.cap_material);
        if (sim.shared())
            fmt::print("shared among {} MPI ranks, slabs along {} (docs/PARALLEL.md)\n", mpi::size(),
                       "xyz"[sim.slabs()->axis()]);
        fmt::print("start: {}\n", describe(s.fill));
        fmt::print("settling (rms grain speed below {} m/s, at most {} s)\n", s.settle_speed, s.settle_max_time);
        if (fields) fmt::print("{}\n", fields->summary());
    }
    DrumLoop loop(sim, std::move(plan), s.output, options.checkpoints, false, options.on_sample,
                  fields ? &*fields : nullptr);
    return loop.run({});
}

DrumOutcome resume_drum(io::Checkpoint checkpoint, const fs::path& dir, bool quiet, double progress_every,
                        double revolutions) {
    DrumPlan plan = load_plan(checkpoint.record);
    plan.quiet = quiet;
    plan.progress = progress_style(quiet, progress_every);
    plan.info.isa = isa_description();  // this machine's, which may differ from the interrupted run's
    const std::int64_t done = plan.rotating ? checkpoint.state.step - plan.rotation_start_step : 0;  // steps
    const double turned = plan.info.omega * static_cast<double>(done) * checkpoint.state.dt / (2.0 * pi);
    if (revolutions > 0.0) lengthen(plan, revolutions, done, checkpoint.state.dt, dir, quiet);
    try {
        check_drum_durations(plan.info.revolutions, plan.info.omega, plan.info.samples_per_revolution,
                             plan.settle_max_time, checkpoint.state.dt);
        if (plan.rotation_start_step < 0 || plan.rotation_start_step > checkpoint.state.step ||
            plan.snapshots_per_revolution < 0 || plan.info.profile_bins < 2)
            throw Error("drum.rotation_start_step, drum.snapshots_per_revolution or profile_bins out of range");
    } catch (const Error& e) {
        throw Error(checkpoint.record.source + ": its record does not fit its state: " + e.what());
    }
    Simulation sim = restore_simulation(checkpoint, dir);
    if (revolutions > 0.0) {
        remove_summary(dir);
        // The run's settings say the new length from now on, not only once it has finished.
        if (plan.rotating && mpi::rank() == 0) io::write_drum_run_info(dir / "drum_run.toml", plan.info);
    }
    if (!quiet && mpi::rank() == 0)
        fmt::print("tumble resume: drum run at step {} (t = {:.6g} s, {})\n", sim.step_count(), sim.time(),
                   plan.rotating ? fmt::format("{:.4g} revolutions", turned) : std::string("settling"));
    std::optional<FieldRecorder> fields = FieldRecorder::resumed(checkpoint.record, sim);
    DrumLoop loop(sim, std::move(plan), dir, load_policy(checkpoint.record), true, {}, fields ? &*fields : nullptr);
    return loop.run(checkpoint.record.numbers("snapshot_times"));
}

void require_drum_run(const std::string& directory, const std::string& command) {
    const fs::path dir(directory);
    std::error_code ec;
    if (fs::exists(dir / "drum_run.toml", ec)) return;
    const std::string what = program_name() + " " + command + " takes the directory of a " + program_name() +
                             " drum run (it has drum_run.toml)";
    if (!fs::is_directory(dir, ec)) throw Error(directory + ": no such directory; " + what);
    if (fs::exists(dir / "run.json", ec))
        throw Error(directory + " is a run of a scenario (" + program_name() + " run: it has run.json), not of " +
                    program_name() + " drum; " + what + ". A scenario run's files are read as they are: "
                    "time_series.csv and snapshots/*.csv with numpy or pandas (tumble.io.Run in Python), "
                    "particles.pvd in ParaView, and " + program_name() + " render " + directory + " draws a movie");
    throw Error(directory + ": not a drum run, or one stopped before its rotation began (no drum_run.toml); " + what);
}

std::string analyze_drum(const std::string& directory, const io::AnalyzeOptions& options) {
    analysis::check_band_options(options.bands);
    // No run at all, then (once the run is this process's to read) a
    // scenario's run; a drum stopped while it settled has no drum_run.toml
    // yet: it is unfinished, below.
    const fs::path dir(directory);
    if (!fs::is_directory(dir)) require_drum_run(directory, "analyze");
    const io::RunLock lock(directory);
    if (!fs::exists(dir / "drum_run.toml") && fs::exists(dir / "run.json")) require_drum_run(directory, "analyze");
    // A stopped or interrupted run: its series end early, and a summary of
    // them would look like that of a finished run (tumble sweep takes it so).
    if (io::resumable(directory, static_cast<std::uintmax_t>(memory_limit_bytes(0.0))))
        throw Error(directory + ": the run is unfinished (its newest checkpoint is not at its end); finish it with " +
                                program_name() + " resume " + directory + ", which analyses it");
    // One stopped before its first checkpoint has none to say so: then only
    // its summary says that it finished.
    if (io::checkpoint_files(directory).empty() && !fs::exists(fs::path(directory) / "summary.json"))
        throw Error(directory + ": the run is unfinished (no checkpoint and no summary.json: it stopped before its "
                                "first checkpoint); run it again");
    require_drum_run(directory, "analyze");
    return io::analyze_drum_run(directory, options);
}

std::string analyze_bands_so_far(const std::string& directory, const analysis::BandOptions& options) {
    analysis::check_band_options(options);
    require_drum_run(directory, "analyze --so-far");
    // The run may be going on (its process holds the run's lock): then what
    // it is writing is left out. One --so-far at a time: the lock of so_far/.
    const std::optional<io::RunLock> run = io::RunLock::if_free(directory);
    const fs::path so_far = fs::path(directory) / "so_far";
    std::error_code ec;
    fs::create_directories(so_far, ec);
    if (ec) throw Error(so_far.string() + ": cannot create the folder: " + ec.message());
    const io::RunLock lock(so_far);
    return io::analyze_bands_so_far(directory, options, !run.has_value());
}

}  // namespace tumble::experiments
