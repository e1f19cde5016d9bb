// SPDX-License-Identifier: MIT
#include "experiments/fields.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "experiments/limits.hpp"
#include "io/checkpoint.hpp"
#include "io/config.hpp"
#include "io/fields_output.hpp"
#include "io/json.hpp"
#include "io/toml_reader.hpp"
#include "io/vtk_output.hpp"
#include "tumble/core/error.hpp"

namespace tumble::experiments {

namespace fs = std::filesystem;

namespace {

bool averaged(const FieldSettings& s, int axis) { return s.average.find("xyz"[axis]) != std::string::npos; }

// More nodes than this are refused outright (the count must fit the
// arithmetic long before any memory limit).
constexpr double max_nodes = 1e12;

}  // namespace

std::string field_settings_problem(const FieldSettings& s) {
    if (s.width && !(std::isfinite(*s.width) && *s.width > 0.0))
        return fmt::format("width: the kernel's width must be a finite number > 0 m, got {}", *s.width);
    if (s.cell && s.cells) return "cell, cells: give the cell size or the cell counts, not both";
    if (s.cell && !(std::isfinite(*s.cell) && *s.cell > 0.0))
        return fmt::format("cell: the cell size must be a finite number > 0 m, got {}", *s.cell);
    for (std::size_t k = 0; k < s.average.size(); ++k)
        if (std::string("xyz").find(s.average[k]) == std::string::npos || s.average.find(s.average[k]) != k)
            return "average: the averaged axes are some of x, y and z, each once, got \"" + s.average + "\"";
    const char* axes = "xyz";
    for (int k = 0; k < 3; ++k) {
        if (s.cells) {
            const double n = (*s.cells)[static_cast<std::size_t>(k)];
            if (!(n >= 1.0 && n <= max_nodes && n == std::floor(n)))
                return fmt::format("cells: a whole number >= 1 along every axis, got {} along {}", n, axes[k]);
            if (averaged(s, k) && n != 1.0)
                return fmt::format("cells: the averaged axis {} has one cell, got {}", axes[k], n);
        }
        if (s.lo && !std::isfinite((*s.lo)[k]))
            return fmt::format("lo: must be finite, got {} along {}", (*s.lo)[k], axes[k]);
        if (s.hi && !std::isfinite((*s.hi)[k]))
            return fmt::format("hi: must be finite, got {} along {}", (*s.hi)[k], axes[k]);
        if (s.lo && s.hi && !((*s.hi)[k] > (*s.lo)[k]))
            return fmt::format("hi: must be above lo along every axis, got hi {} <= lo {} along {}", (*s.hi)[k],
                               (*s.lo)[k], axes[k]);
    }
    if (!(std::isfinite(s.max_memory_gib) && s.max_memory_gib >= 0.0))
        return fmt::format("max_memory_gib: must be a finite number >= 0, got {}", s.max_memory_gib);
    return {};
}

double field_memory_bytes(const FieldSettings& s, const analysis::CgGrid& g) {
    return analysis::cg_memory_bytes(g.nodes()) + (s.vti ? io::fields_file_bytes(g.nodes()) : 0.0);
}

std::string grid_summary(const FieldSettings& s, const analysis::CgGrid& g) {
    return fmt::format("{} x {} x {} nodes ({}), {:.3g} MiB", g.cells[0], g.cells[1], g.cells[2], g.nodes(),
                       field_memory_bytes(s, g) / (1024.0 * 1024.0));
}

namespace {

// The grid of settings whose lo, hi and width are known.
analysis::CgSettings complete(const FieldSettings& s, const Vec3& lo, Vec3 hi, double width,
                              const std::string& memory_option, const Domain* domain = nullptr) {
    if (const std::string problem = field_settings_problem(s); !problem.empty()) throw Error(problem);
    analysis::CgSettings out;
    out.kernel = s.kernel;
    out.width = width;
    double nodes = 1.0;
    std::array<double, 3> count{};
    for (int k = 0; k < 3; ++k) {
        const auto axis = static_cast<std::size_t>(k);
        out.grid.averaged[axis] = averaged(s, k);
        out.grid.periodic[axis] = out.grid.averaged[axis] && domain && domain->periodic[axis] &&
                                  lo[k] == domain->lo[k] && hi[k] == domain->hi[k];
        if (!(hi[k] > lo[k]))
            throw Error(fmt::format("hi: must be above lo along every axis, got hi {} <= lo {} along {}", hi[k], lo[k],
                                    "xyz"[k]));
        if (out.grid.averaged[axis]) count[axis] = 1.0;
        else if (s.cells) count[axis] = (*s.cells)[axis];
        else {
            const double cell = s.cell.value_or(width);
            count[axis] = std::max(1.0, std::ceil((hi[k] - lo[k]) / cell * (1.0 - 1e-12)));
            if (count[axis] <= max_nodes) hi[k] = lo[k] + count[axis] * cell;
        }
        nodes *= count[axis];
    }
    const std::string driver = fmt::format("a grid of {:g} x {:g} x {:g} nodes ({})", count[0], count[1], count[2],
                                           s.cells ? "cells" : (s.cell ? "cell" : "cell = width"));
    if (!(nodes <= max_nodes))
        throw Error(fmt::format("{}: {}, more than any memory holds", s.cells ? "cells" : "cell", driver));
    for (std::size_t k = 0; k < 3; ++k) out.grid.cells[k] = static_cast<std::size_t>(count[k]);
    out.grid.lo = lo;
    out.grid.hi = hi;
    if (const std::string problem = analysis::cg_settings_problem(out); !problem.empty()) throw Error(problem);
    check_memory({field_memory_bytes(s, out.grid), driver}, memory_limit_bytes(s.max_memory_gib), "fields", memory_option);
    return out;
}

}  // namespace

std::optional<analysis::CgSettings> grid_settings(const FieldSettings& s, const std::string& memory_option) {
    if (const std::string problem = field_settings_problem(s); !problem.empty()) throw Error(problem);
    if (!s.lo || !s.hi || !s.width) return std::nullopt;
    return complete(s, *s.lo, *s.hi, *s.width, memory_option);
}

analysis::CgSettings grid_settings(const FieldSettings& s, const analysis::CgGrains& grains,
                                   const std::string& memory_option, const Domain* domain) {
    if (const std::string problem = field_settings_problem(s); !problem.empty()) throw Error(problem);
    const std::size_t n = grains.position.size();
    if (n == 0 && (!s.lo || !s.hi || !s.width))
        throw Error("lo, hi, width: no grains to take them from; give them");
    constexpr double inf = std::numeric_limits<double>::infinity();
    Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    double radii = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double R = grains.radius[i];
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], grains.position[i][k] - R);
            hi[k] = std::max(hi[k], grains.position[i][k] + R);
        }
        radii += R;
    }
    for (int k = 0; k < 3; ++k)
        if (domain && domain->periodic[static_cast<std::size_t>(k)] && averaged(s, k))
            lo[k] = domain->lo[k], hi[k] = domain->hi[k];
    return complete(s, s.lo.value_or(lo), s.hi.value_or(hi), s.width.value_or(radii / static_cast<double>(n)),
                    memory_option, domain);
}

namespace {

io::LoadedCheckpoint load_checkpoint(const fs::path& run_directory, const fs::path& file) {
    const auto max_bytes = static_cast<std::uintmax_t>(memory_limit_bytes(0.0));
    if (!file.empty()) {
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) throw Error("checkpoint: no such file: " + file.string());
        io::LoadedCheckpoint loaded;
        loaded.checkpoint = io::decode_checkpoint(io::read_text_file(file, max_bytes), file.string());
        loaded.file = file;
        return loaded;
    }
    return io::newest_checkpoint_kind(run_directory, max_bytes).ranks > 1
               ? io::load_whole_checkpoint(run_directory, max_bytes)
               : io::load_newest_checkpoint(run_directory, max_bytes);
}

}  // namespace

namespace {

// What is wrong with the frame, the span and the averaged axes the drum
// frame needs (after a run and during one), naming the key; "" if nothing.
std::string frame_settings_problem(const std::string& frame, double span, const std::string& average) {
    if (frame != "lab" && frame != "drum") return "frame: lab or drum, got \"" + frame + "\"";
    if (!(std::isfinite(span) && span > 0.0 && span <= 1.0))
        return fmt::format("span: the middle part of the free surface that the drum frame averages, a number in (0, 1], "
                           "got {}", span);
    if (frame == "drum" && !average.empty() && average != "z")
        return "average: the drum frame's cross-section is averaged along z, the drum's axis (give z or nothing), got \"" +
               average + "\"";
    return {};
}

}  // namespace

std::string frame_problem(const RunFieldsOptions& o) {
    if (const std::string problem = frame_settings_problem(o.frame, o.span, o.settings.average); !problem.empty())
        return problem;
    for (const double n : o.frame_cells)
        if (!(n >= 1.0 && n <= max_nodes && n == std::floor(n)))
            return fmt::format("frame_cells: the cells along s and z, whole numbers >= 1, got {}", n);
    if (o.frame == "lab" && (o.frame_cells[0] != 1.0 || o.frame_cells[1] != 1.0))
        return "frame_cells: a grid in the drum's coordinates, for the drum frame (frame drum) only";
    return {};
}

namespace {

// The samples' states: `samples` steps `between` steps apart, taken with
// the contacts recorded, from the checkpoint's state; each handed to `take`.
// The same checkpoint gives the same states every time (the simulation is
// deterministic), so a second pass needs no copy of the first's states.
void for_each_sample(io::Checkpoint checkpoint, int samples, double every,
                     const std::function<void(const analysis::GrainState&, const Simulation&)>& take) {
    Simulation sim(std::move(checkpoint.scenario));
    sim.restore(std::move(checkpoint.state));
    const std::int64_t between = samples > 1 ? step_count(every, sim.dt(), "every") : 1;
    for (int k = 0; k < samples; ++k) {
        if (k > 0 && between > 1) {
            sim.set_contact_recording(false);
            sim.advance(between - 1);
        }
        sim.set_contact_recording(true);
        sim.step();
        take(analysis::grain_state(sim), sim);
    }
}

// The depth profile's grid for the surface of cross-section `cs` (of
// settings `c`; its grain centres reach `reach` from the axis, their radii
// are `largest` at most): d from 3 widths above the surface to the deepest
// grain surface there can be under it, where the circle the grain centres
// reach is deepest (d = level + reach), at the cross-section's cell size;
// averaged along s over the middle `span` of the chord and along z.
analysis::CgSettings profile_settings(const analysis::Fields& cs, const analysis::CgSettings& c,
                                      const analysis::DrumSurface& surface, double reach, double largest, double span) {
    const double half = span * surface.half_length, w = c.width, cell = cs.grid.spacing(0);
    const double deepest = surface.level + reach + largest;
    analysis::CgSettings p;
    p.kernel = c.kernel;
    p.width = w;
    p.grid.averaged = {true, false, true};
    p.grid.periodic = {false, false, cs.grid.periodic[2]};
    const double cells = std::max(2.0, std::ceil((deepest + 3.0 * w) / cell));
    p.grid.cells = {1, static_cast<std::size_t>(cells), 1};
    p.grid.lo = {-half, -3.0 * w, cs.grid.lo.z};
    p.grid.hi = {half, -3.0 * w + cells * cell, cs.grid.hi.z};
    return p;
}

// The profile's depth nodes at two points across the span: the velocity
// gradient along s, for the shear rate (use_in_plane_shear_rate).
analysis::CgSettings two_across(analysis::CgSettings p) {
    p.grid.cells[0] = 2;
    p.grid.averaged[0] = false;
    return p;
}

// The drum frame's depth profile (RunFieldsOptions) of the samples of
// `checkpoint`: the surface found on their cross-section `cs` (of settings
// `c`, reach and largest as profile_settings), the samples taken again,
// carried into the drum's coordinates and coarse-grained on a grid
// resolved along d.
DrumLayer drum_layer(const analysis::Fields& cs, const analysis::CgSettings& c, double reach, double largest,
                     io::Checkpoint checkpoint, const RunFieldsOptions& o) {
    DrumLayer out;
    out.surface = analysis::find_drum_surface(cs, reach, o.span);
    const analysis::CgSettings p = profile_settings(cs, c, out.surface, reach, largest, o.span);
    const double cells = static_cast<double>(p.grid.cells[1]);
    // The resolved grid: the profile's, with frame_cells along s and z.
    std::optional<analysis::FieldAccumulator> resolved;
    if (o.frame_cells[0] > 1.0 || o.frame_cells[1] > 1.0) {
        analysis::CgSettings r = p;
        r.grid.cells = {static_cast<std::size_t>(o.frame_cells[0]), p.grid.cells[1],
                        static_cast<std::size_t>(o.frame_cells[1])};
        r.grid.averaged = {r.grid.cells[0] == 1, false, r.grid.cells[2] == 1};
        r.grid.periodic = {false, false, r.grid.averaged[2] && p.grid.periodic[2]};
        const double nodes = o.frame_cells[0] * cells * o.frame_cells[1];
        if (!(nodes <= max_nodes)) throw Error("frame_cells: more nodes than any memory holds");
        check_memory({analysis::cg_memory_bytes(r.grid.nodes()),
                      fmt::format("a grid of {:g} x {:g} x {:g} nodes in the drum's coordinates (frame_cells)",
                                  o.frame_cells[0], cells, o.frame_cells[1])},
                     memory_limit_bytes(o.settings.max_memory_gib), "fields", o.memory_option);
        resolved.emplace(r);
    }
    analysis::FieldAccumulator sum(p), across(two_across(p));
    for_each_sample(std::move(checkpoint), o.samples, o.every, [&](const analysis::GrainState& s, const Simulation&) {
        const analysis::GrainState in_frame = analysis::to_drum_frame(s, out.surface);
        sum.add(in_frame.grains(), in_frame.contacts);
        across.add(in_frame.grains(), in_frame.contacts);
        if (resolved) resolved->add(in_frame.grains(), in_frame.contacts);
    });
    out.profile = std::move(sum).finish();
    analysis::use_in_plane_shear_rate(out.profile, std::move(across).finish());
    out.layer = analysis::flowing_layer(out.profile);
    if (resolved) out.resolved = std::move(*resolved).finish();
    return out;
}

// The drum frame of cross-section `cs` averaged in the lab during a run
// (FieldRecorder): the surface found on it, the profile carried from it
// (analysis::drum_profile_of), at the grid drum_layer takes.
DrumLayer drum_layer_of_average(const analysis::Fields& cs, const analysis::CgSettings& c, double reach,
                                double largest, double span) {
    DrumLayer out;
    out.surface = analysis::find_drum_surface(cs, reach, span);
    const analysis::CgSettings p = profile_settings(cs, c, out.surface, reach, largest, span);
    out.profile = analysis::drum_profile_of(cs, out.surface, p);
    analysis::use_in_plane_shear_rate(out.profile, analysis::drum_profile_of(cs, out.surface, two_across(p)));
    out.layer = analysis::flowing_layer(out.profile);
    return out;
}

}  // namespace

RunFields run_fields(const RunFieldsOptions& given, const std::function<void(const std::string&)>& say) {
    RunFieldsOptions o = given;
    if (const std::string problem = frame_problem(o); !problem.empty()) throw Error(problem);
    const bool drum = o.frame == "drum";
    if (drum) o.settings.average = std::string(1, 'z');  // (not = "z": GCC 12 warns falsely, -Wrestrict)
    if (const std::string problem = field_settings_problem(o.settings); !problem.empty()) throw Error(problem);
    if (o.samples < 1) throw Error(fmt::format("samples: at least 1, got {}", o.samples));
    if (o.samples > 1 && !(std::isfinite(o.every) && o.every > 0.0))
        throw Error(fmt::format("every: the time between samples must be a finite number > 0 s, got {}", o.every));
    std::error_code ec;
    if (!fs::is_directory(o.run_directory, ec))
        throw Error("run directory: no such directory: " + o.run_directory.string());
    if (drum && !fs::exists(o.run_directory / "drum_run.toml", ec))
        throw Error("frame: drum takes the directory of a tumble drum run (it has drum_run.toml); " +
                    o.run_directory.string() + " has none");
    // A grid given in full is checked, its memory too, before the checkpoint is read.
    if (const auto early = grid_settings(o.settings, o.memory_option))
        say("grid " + grid_summary(o.settings, early->grid));

    io::LoadedCheckpoint loaded = load_checkpoint(o.run_directory, o.checkpoint);
    say("states from " + loaded.file.string());
    RunFields out;
    out.checkpoint = loaded.file;
    std::optional<analysis::FieldAccumulator> sum;
    analysis::CgSettings settings;
    double reach = 0.0, largest = 0.0;  // m: the largest distance of a grain centre from the z axis, radius
    // The drum frame takes the samples twice: the first pass a copy of the
    // checkpoint, the second the checkpoint itself.
    for_each_sample(drum ? io::Checkpoint(loaded.checkpoint) : std::move(loaded.checkpoint), o.samples, o.every,
                    [&](const analysis::GrainState& state, const Simulation& sim) {
        if (!sum) {
            settings = grid_settings(o.settings, state.grains(), o.memory_option, &sim.scenario().domain);
            if (!o.settings.lo || !o.settings.hi || !o.settings.width)
                say("grid " + grid_summary(o.settings, settings.grid));
        }
        const auto start = std::chrono::steady_clock::now();
        if (!sum) sum.emplace(settings);  // its allocation counts: a large grid's memory takes time to map
        sum->add(state.grains(), state.contacts);
        out.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out.times.push_back(state.time);
        for (std::size_t i = 0; i < state.position.size(); ++i) {
            reach = std::max(reach, std::hypot(state.position[i].x, state.position[i].y));
            largest = std::max(largest, state.radius[i]);
        }
    });
    const auto start = std::chrono::steady_clock::now();
    out.fields = std::move(*sum).finish();
    out.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (drum) {
        say("the drum frame: the samples again, in the free surface's coordinates");
        out.drum = drum_layer(out.fields, settings, reach, largest, std::move(loaded.checkpoint), o);
    }
    return out;
}


void write_fields_files(const fs::path& out, const analysis::Fields& fields, const std::string& format) {
    fs::create_directories(out);
    if (format != "csv") io::write_vti_fields(out / "fields.vti", fields);
    if (format != "vti") io::write_fields_csv(out / "fields.csv", fields);
}

void write_drum_layer_files(const fs::path& out, const DrumLayer& layer, double span) {
    fs::create_directories(out);
    io::write_fields_csv(out / "profile.csv", layer.profile, "sdz");
    if (layer.resolved) io::write_fields_csv(out / "frame.csv", *layer.resolved, "sdz");
    io::write_json_file(out / "drum_frame.json", io::drum_frame_json(layer.surface, layer.layer, span));
}

std::string drum_layer_summary(const DrumLayer& layer) {
    const analysis::DrumSurface& s = layer.surface;
    const analysis::FlowingLayer& l = layer.layer;
    const std::string thickness =
        std::isfinite(l.thickness)
            ? fmt::format("flowing layer {:.3g} m ({:.2f} grain diameters) deep", l.thickness, l.thickness / l.diameter)
            : std::string("no flowing layer (the velocity along the surface does not turn below it)");
    return fmt::format("free surface at {:.2f} degrees, {:.4g} m from the axis; surface velocity {:.3g} m/s, {}",
                       s.angle * 180.0 / std::numbers::pi, s.level, l.surface_velocity, thickness);
}

namespace {

// A number of a KEY=VALUE item, the whole value.
double number_of(const std::string& key, const std::string& value) {
    std::size_t used = 0;
    double x = 0.0;
    try {
        x = std::stod(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != value.size()) throw Error("fields: " + key + ": not a number: \"" + value + "\"");
    return x;
}

// Three numbers X,Y,Z.
std::array<double, 3> triple_of(const std::string& key, const std::string& value) {
    std::array<double, 3> out{};
    std::size_t start = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t comma = value.find(',', start);
        if ((k < 2) == (comma == std::string::npos))
            throw Error("fields: " + key + ": three numbers X,Y,Z, got \"" + value + "\"");
        out[k] = number_of(key, value.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

}  // namespace

FieldsDuringRun parse_fields_during_run(const std::vector<std::string>& items) {
    FieldsDuringRun o;
    for (const std::string& item : items) {
        std::istringstream words(item);
        for (std::string word; words >> word;) {
            const std::size_t eq = word.find('=');
            if (eq == std::string::npos || eq == 0)
                throw Error("fields: KEY=VALUE items, got \"" + word + "\"");
            const std::string key = word.substr(0, eq), value = word.substr(eq + 1);
            FieldSettings& f = o.settings;
            if (key == "every") o.every = number_of(key, value);
            else if (key == "from") o.from = number_of(key, value);
            else if (key == "samples") {
                const double n = number_of(key, value);
                if (!(n >= 1.0 && n <= 1e9 && n == std::floor(n)))
                    throw Error("fields: samples: a whole number >= 1, got " + value);
                o.samples = static_cast<int>(n);
            } else if (key == "lo") {
                const auto v = triple_of(key, value);
                f.lo = Vec3{v[0], v[1], v[2]};
            } else if (key == "hi") {
                const auto v = triple_of(key, value);
                f.hi = Vec3{v[0], v[1], v[2]};
            } else if (key == "cell") f.cell = number_of(key, value);
            else if (key == "cells") f.cells = triple_of(key, value);
            else if (key == "average") f.average = value;
            else if (key == "width") f.width = number_of(key, value);
            else if (key == "kernel") {
                if (value != "gaussian" && value != "lucy")
                    throw Error("fields: kernel: gaussian or lucy, got \"" + value + "\"");
                f.kernel = value == "lucy" ? analysis::CgKernel::lucy : analysis::CgKernel::gaussian;
            } else if (key == "format") {
                if (value != "vti" && value != "csv" && value != "both")
                    throw Error("fields: format: vti, csv or both, got \"" + value + "\"");
                o.format = value;
            } else if (key == "frame") o.frame = value;
            else if (key == "span") o.span = number_of(key, value);
            else
                throw Error("fields: " + key + ": no such key; the keys are " +
                            fmt::format("{}", fmt::join(io::field_keys, ", ")));
        }
    }
    if (const std::string problem = frame_settings_problem(o.frame, o.span, o.settings.average); !problem.empty())
        throw Error("fields: " + problem);
    o.settings.vti = o.format != "csv";
    return o;
}

FieldRecorder::FieldRecorder(const std::vector<std::string>& items, const Simulation& sim, std::int64_t last_step,
                             double max_memory_gib, bool drum)
    : items_(items), options_(parse_fields_during_run(items)), dt_(sim.dt()) {
    FieldsDuringRun& o = options_;
    o.settings.max_memory_gib = max_memory_gib;
    if (sim.shared()) throw Error("fields: taken during a run on one MPI rank only; take them afterwards with tumble fields");
    if (o.frame == "drum") {  // (its averaged axes checked by parse_fields_during_run)
        if (!drum)
            throw Error("fields: frame: drum takes a run of tumble drum (its axis is the drum frame's z); this run "
                        "is not one");
        o.settings.average = std::string(1, 'z');
    }
    if (const std::string problem = field_settings_problem(o.settings); !problem.empty())
        throw Error("fields: " + problem);
    if (!(std::isfinite(o.every) && o.every > 0.0))
        throw Error(fmt::format("fields: every: the time between the states must be a finite number > 0 s, got {}",
                                o.every));
    if (!(std::isfinite(o.from) && o.from >= 0.0))
        throw Error(fmt::format("fields: from: a finite time >= 0 s, got {}", o.from));
    between_ = std::max<std::int64_t>(1, step_count(o.every, dt_, "fields: every"));
    first_ = std::max<std::int64_t>({1, sim.step_count() + 1, step_count(o.from, dt_, "fields: from")});
    if (last_step > 0 && first_ > last_step)
        throw Error(fmt::format("fields: from: {} s is after the run's end, {:.6g} s", o.from,
                                static_cast<double>(last_step) * dt_));
    const Domain& domain = sim.scenario().domain;
    const analysis::GrainState start = analysis::grain_state(sim);
    Vec3 lo = domain.lo, hi = domain.hi;
    if (o.frame == "drum" && !start.radius.empty()) {
        // The profile is carried from the cross-section, so the
        // cross-section holds the kernel of every grain whole: 3 widths
        // beyond the drum's box across its axis (m).
        double mean = 0.0;
        for (const double R : start.radius) mean += R / static_cast<double>(start.radius.size());
        const double reach = 3.0 * o.settings.width.value_or(mean);
        for (int k = 0; k < 2; ++k) lo[k] -= reach, hi[k] += reach;
    }
    o.settings.lo = o.settings.lo.value_or(lo);
    o.settings.hi = o.settings.hi.value_or(hi);
    try {
        settings_ = grid_settings(o.settings, start.grains(), "--max-memory GIB", &domain);
    } catch (const Error& e) {  // named as a key of --fields (the memory's message names fields already)
        const std::string why = e.what();
        throw Error(why.starts_with("fields: ") ? why : "fields: " + why);
    }
    sum_.emplace(settings_);
}

void FieldRecorder::save(io::CheckpointRecord& record) const {
    if (!sum_) return;  // written: the run has ended
    std::string items;
    for (const std::string& item : items_) items += item + "\n";
    record.set("fields.items", items);
    const analysis::CgGrid& g = settings_.grid;
    std::vector<double> grid;
    for (int k = 0; k < 3; ++k) grid.push_back(g.lo[k]);
    for (int k = 0; k < 3; ++k) grid.push_back(g.hi[k]);
    for (std::size_t k = 0; k < 3; ++k) grid.push_back(static_cast<double>(g.cells[k]));
    for (std::size_t k = 0; k < 3; ++k) grid.push_back(g.averaged[k] ? 1.0 : 0.0);
    for (std::size_t k = 0; k < 3; ++k) grid.push_back(g.periodic[k] ? 1.0 : 0.0);
    grid.push_back(settings_.kernel == analysis::CgKernel::lucy ? 1.0 : 0.0);
    grid.push_back(settings_.width);
    record.set("fields.grid", grid);
    record.set("fields.steps", std::vector<double>{static_cast<double>(first_), static_cast<double>(between_)});
    record.set("fields.times", times_);
    record.set("fields.sums", sum_->sums());
    record.set("fields.reach", std::vector<double>{reach_, largest_});
}

std::optional<FieldRecorder> FieldRecorder::resumed(const io::CheckpointRecord& record, const Simulation& sim) {
    if (!record.has("fields.items")) return std::nullopt;
    const auto bad = [&](const std::string& why) {
        return Error(record.source + ": its fields taken during the run do not fit together: " + why);
    };
    FieldRecorder r;
    std::istringstream lines(record.text("fields.items"));
    for (std::string item; std::getline(lines, item);) r.items_.push_back(item);
    r.options_ = parse_fields_during_run(r.items_);
    r.dt_ = sim.dt();
    const std::vector<double>& grid = record.numbers("fields.grid");
    const std::vector<double>& steps = record.numbers("fields.steps");
    if (grid.size() != 17 || steps.size() != 2) throw bad("fields.grid or fields.steps has the wrong length");
    analysis::CgSettings& c = r.settings_;
    for (std::size_t k = 0; k < 3; ++k) {
        c.grid.lo[static_cast<int>(k)] = grid[k];
        c.grid.hi[static_cast<int>(k)] = grid[3 + k];
        if (!(grid[6 + k] >= 1.0 && grid[6 + k] <= 1e12 && grid[6 + k] == std::floor(grid[6 + k])))
            throw bad("fields.grid: cells not a whole number >= 1");
        c.grid.cells[k] = static_cast<std::size_t>(grid[6 + k]);
        c.grid.averaged[k] = grid[9 + k] != 0.0;
        c.grid.periodic[k] = grid[12 + k] != 0.0;
    }
    c.kernel = grid[15] != 0.0 ? analysis::CgKernel::lucy : analysis::CgKernel::gaussian;
    c.width = grid[16];
    if (const std::string problem = analysis::cg_settings_problem(c); !problem.empty()) throw bad(problem);
    if (!(steps[0] >= 1.0 && steps[1] >= 1.0 && steps[0] <= 9e15 && steps[1] <= 9e15))
        throw bad("fields.steps out of range");
    r.first_ = static_cast<std::int64_t>(steps[0]);
    r.between_ = static_cast<std::int64_t>(steps[1]);
    r.times_ = record.numbers("fields.times");
    if (record.has("fields.reach")) {  // (checkpoints from before the drum frame during a run have none)
        const std::vector<double>& reach = record.numbers("fields.reach");
        if (reach.size() != 2) throw bad("fields.reach has the wrong length");
        r.reach_ = reach[0], r.largest_ = reach[1];
    }
    check_memory({field_memory_bytes(r.options_.settings, c.grid), "the grid of the fields taken during the run"},
                 memory_limit_bytes(0.0), record.source, "tumble resume's limit");
    r.sum_.emplace(c);
    try {
        r.sum_->restore(record.numbers("fields.sums"), r.times_.size());
    } catch (const Error& e) {
        throw bad(e.what());
    }
    return r;
}

std::string FieldRecorder::summary() const {
    return fmt::format("fields: grid {}; a state every {} steps from step {}{}", grid_summary(options_.settings, grid()),
                       between_, first_,
                       options_.samples > 0 ? fmt::format(", {} states at most", options_.samples) : std::string());
}

void FieldRecorder::advance(Simulation& sim, std::int64_t steps) {
    const std::int64_t end = sim.step_count() + steps;
    while (sim.step_count() < end) {
        const bool more = options_.samples == 0 || times_.size() < static_cast<std::size_t>(options_.samples);
        const std::int64_t next = first_ + std::max<std::int64_t>(0, (sim.step_count() - first_ + between_) / between_) * between_;
        if (!more || next > end) {
            sim.advance(end - sim.step_count());
            return;
        }
        if (next - 1 > sim.step_count()) sim.advance(next - 1 - sim.step_count());
        sim.set_contact_recording(true);
        sim.step();
        sim.set_contact_recording(false);
        const analysis::GrainState state = analysis::grain_state(sim);
        sum_->add(state.grains(), state.contacts);
        times_.push_back(state.time);
        for (std::size_t i = 0; i < state.position.size(); ++i) {
            reach_ = std::max(reach_, std::hypot(state.position[i].x, state.position[i].y));
            largest_ = std::max(largest_, state.radius[i]);
        }
    }
}

std::string FieldRecorder::write(const fs::path& run_directory) {
    if (times_.empty())
        throw Error(fmt::format("fields: from: no state was taken; the run ended before {} s", options_.from));
    const bool drum = options_.frame == "drum";
    const fs::path out = run_directory / (drum ? "flowing_layer" : "fields");
    const analysis::Fields fields = std::move(*sum_).finish();
    sum_.reset();
    write_fields_files(out, fields, options_.format);
    std::string said = fmt::format("fields: {} state{} from t = {:.6g} s to {:.6g} s into {}", times_.size(),
                                   times_.size() == 1 ? "" : "s", times_.front(), times_.back(), out.string());
    if (drum) {
        // The cross-section is written whatever the surface: a bed too
        // shallow or too loose for one says so and the run still ends well.
        try {
            const DrumLayer layer = drum_layer_of_average(fields, settings_, reach_, largest_, options_.span);
            write_drum_layer_files(out, layer, options_.span);
            said += "\nfields: " + drum_layer_summary(layer);
        } catch (const Error& e) {
            said += fmt::format("\nfields: no drum frame (the cross-section is written): {}", e.what());
        }
    }
    return said;
}

}  // namespace tumble::experiments
