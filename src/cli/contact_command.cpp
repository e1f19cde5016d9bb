// SPDX-License-Identifier: MIT
// tumble contact: what each kind of contact of a scenario or of the drum
// does, and why the time step is what it is (docs/MODEL.md "tumble contact").
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/drum_setup.hpp"
#include "experiments/limits.hpp"
#include "io/config.hpp"
#include "io/json.hpp"
#include "tumble/analysis/pair_collision.hpp"

namespace tumble::cli {

namespace {

using io::Json;

const char* partner_name(Partner p) {
    switch (p) {
        case Partner::free: return "free";
        case Partner::kinematic: return "kinematic";
        case Partner::flat_wall: return "flat wall";
    }
    return "";
}

Json collision_json(const analysis::Collision& c) {
    return Json{{"separated", c.separated}, {"restitution", c.restitution}, {"contact_time", c.contact_time}};
}

// A cell of the table: the value, or "no rebound" when the pair never parted.
std::string cell(const analysis::Collision& c, double value, const char* format) {
    return c.separated ? fmt::format(fmt::runtime(format), value) : std::string("no rebound");
}

void print_table(const analysis::ContactReport& report) {
    const TimeStepReport& t = report.time_step;
    fmt::print("time step {:.4g} s ({}), set by {}\n", t.dt, t.automatic ? "automatic" : "given",
               t.automatic ? t.recommended_by : "the scenario");
    fmt::print("largest safe step {:.4g} s, set by {}\n", t.maximum, t.limiting);
    for (const analysis::PairContactReport& r : report.pairs) {
        const analysis::NormalLaw& law = r.law;
        fmt::print("\n{}: R* = {:.4g} mm, m* = {:.4g} g, E* = {:.4g} MPa, B* = {:.4g} Pa s\n", r.pair.name,
                   law.R_star * 1e3, law.m_star * 1e3, law.E_star * 1e-6, law.B_star);
        // A time, and the step in its units; "off" with its term.
        auto time = [&](const char* name, const char* symbol, double value) {
            return std::isfinite(value)
                       ? fmt::format("{} {} {:.4g} ms (dt = {:.3g} {})", name, symbol, value * 1e3, t.dt / value, symbol)
                       : fmt::format("{} off", name);
        };
        fmt::print("  at {:.3g} m/s: {}, {}, {}\n", report.reference_speed,
                   time("Hertz collision time", "t_c", r.times.collision), time("viscous time", "m*/c", r.times.viscous),
                   std::isfinite(r.times.creep) ? time("creep time", "tau", r.times.creep) : "not over-damped");
        fmt::print("  tangential spring ({} stiffness): {}\n",
                   keyword_of(tangential_stiffnesses, report.tangential_stiffness),
                   time("half period", "t_t", r.times.tangential));
        fmt::print("  equilibrium overlap {:.4g} um ({:.3g} % of R*), pull-off force {:.4g} mN\n",
                   r.equilibrium_overlap * 1e6, 100.0 * r.equilibrium_overlap / law.R_star, r.pull_off_force * 1e3);
        if (law.attraction <= 0.0)
            fmt::print("  no attraction: grains rebound at every speed\n");
        else if (r.sticking_speed >= analysis::max_sticking_speed)
            fmt::print("  sticks at every impact speed up to {} m/s (no rebound with the attraction on)\n",
                       analysis::max_sticking_speed);
        else
            fmt::print("  sticks below {:.4g} m/s (with the attraction on)\n", r.sticking_speed);
        fmt::print("  without attraction:  speed    restitution            contact time (ms)\n");
        fmt::print("                       (m/s)    at dt     converged    at dt     converged\n");
        for (const analysis::Impact& i : r.impacts)
            fmt::print("                       {:<8.3g} {:<9} {:<12} {:<9} {}\n", i.speed,
                       cell(i.at_step, i.at_step.restitution, "{:.4g}"),
                       cell(i.converged, i.converged.restitution, "{:.4g}"),
                       cell(i.at_step, i.at_step.contact_time * 1e3, "{:.4g}"),
                       cell(i.converged, i.converged.contact_time * 1e3, "{:.4g}"));
    }
}

// An infinite time (its term is off) is null (io/json.hpp).
void print_json(const analysis::ContactReport& report) {
    const TimeStepReport& t = report.time_step;
    Json pairs = Json::array();
    for (const analysis::PairContactReport& r : report.pairs) {
        Json impacts = Json::array();
        for (const analysis::Impact& i : r.impacts)
            impacts.push_back(Json{{"speed", i.speed},
                                   {"at_step", collision_json(i.at_step)},
                                   {"converged", collision_json(i.converged)}});
        const analysis::NormalLaw& law = r.law;
        pairs.push_back(Json{{"pair", r.pair.name},
                             {"partner", partner_name(r.pair.partner)},
                             {"R_star", law.R_star},
                             {"m_star", law.m_star},
                             {"E_star", law.E_star},
                             {"B_star", law.B_star},
                             {"attraction", law.attraction},
                             {"hertz_collision_time", r.times.collision},
                             {"viscous_time", r.times.viscous},
                             {"creep_time", r.times.creep},  // null where not over-damped
                             {"tangential_time", r.times.tangential},  // null without shear or friction
                             {"equilibrium_overlap", r.equilibrium_overlap},
                             {"pull_off_force", r.pull_off_force},
                             {"sticking_speed", r.sticking_speed},
                             {"sticks_at_every_speed",
                              law.attraction > 0.0 && r.sticking_speed >= analysis::max_sticking_speed},
                             {"impacts", impacts}});
    }
    fmt::print("{}\n", io::json_line(Json{{"dt", t.dt},
                                          {"automatic", t.automatic},
                                          {"dt_set_by", t.automatic ? t.recommended_by : "given"},
                                          {"reference_speed", report.reference_speed},
                                          {"tangential_stiffness",
                                           keyword_of(tangential_stiffnesses, report.tangential_stiffness)},
                                          {"maximum_dt", t.maximum},
                                          {"maximum_set_by", t.limiting},
                                          {"pairs", pairs}}));
}

}  // namespace

int contact_command(const ContactOptions& options) {
    const Scenario scenario = options.scenario_file.empty() ? build_drum(options.drum, options.allow_unsafe_dt).scenario
                                                            : io::load_run_config(options.scenario_file).scenario;
    // tumble run's checks of the materials and the step they give, before
    // any collision is computed.
    const std::string source = options.scenario_file.empty() ? "command line" : options.scenario_file;
    experiments::check_time_step(assess_time_step(scenario), source);
    experiments::check_stiffness(scenario, options.allow_soft, source);
    const analysis::ContactReport report = analysis::contact_report(scenario, options.speeds);
    if (options.json)
        print_json(report);
    else
        print_table(report);
    return 0;
}

}  // namespace tumble::cli
