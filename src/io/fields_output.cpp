// SPDX-License-Identifier: MIT
#include "io/fields_output.hpp"

#include <cmath>

#include <fmt/format.h>

#include "io/output.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::io {

namespace {

// A field's doubles node by node: a Vec3 is 3 doubles, a Tensor 9, in order.
static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(analysis::Tensor) == 9 * sizeof(double));

template <class T>
std::span<const double> doubles(const std::vector<T>& v) {
    return {reinterpret_cast<const double*>(v.data()), v.size() * sizeof(T) / sizeof(double)};
}

FieldColumn scalar(std::string name, const std::vector<double>& v) { return {std::move(name), {""}, doubles(v)}; }
FieldColumn vector(std::string name, const std::vector<Vec3>& v, const std::string& axes) {
    std::vector<std::string> components;
    for (const char a : axes) components.emplace_back(1, a);
    return {std::move(name), components, doubles(v)};
}
// Row by row: (a, b) is "ab".
FieldColumn tensor(std::string name, const std::vector<analysis::Tensor>& v, const std::string& axes) {
    std::vector<std::string> components;
    for (const char a : axes)
        for (const char b : axes) components.push_back({a, b});
    return {std::move(name), components, doubles(v)};
}

// The doubles per node of every field.
constexpr double doubles_per_node = 9 + 2 * 3 + 3 * 9;

}  // namespace

std::vector<FieldColumn> field_columns(const analysis::Fields& f, const std::string& axes) {
    std::vector<FieldColumn> columns;
    columns.push_back(scalar("solid_fraction", f.solid_fraction));
    columns.push_back(scalar("density", f.density));
    columns.push_back(scalar("diameter", f.diameter));
    columns.push_back(vector("velocity", f.velocity, axes));
    columns.push_back(vector("momentum", f.momentum, axes));
    columns.push_back(scalar("temperature", f.temperature));
    columns.push_back(scalar("pressure", f.pressure));
    columns.push_back(scalar("shear_stress", f.shear_stress));
    columns.push_back(scalar("shear_rate", f.shear_rate));
    columns.push_back(scalar("inertial_number", f.inertial_number));
    columns.push_back(scalar("friction", f.friction));
    columns.push_back(tensor("stress", f.stress, axes));
    columns.push_back(tensor("kinetic_stress", f.kinetic_stress, axes));
    columns.push_back(tensor("contact_stress", f.contact_stress, axes));
    return columns;
}

double fields_file_bytes(std::size_t nodes) {
    // zlib's deflate adds at most 5 bytes per 16 kB block it cannot compress.
    return 1.001 * doubles_per_node * 8.0 * static_cast<double>(nodes);
}

namespace {

// The CSV rows into `stream`, a block of rows at a time.
void write_rows(std::ofstream& stream, const std::filesystem::path& part, const analysis::Fields& f,
                const std::string& axes) {
    const std::vector<FieldColumn> columns = field_columns(f, axes);
    fmt::memory_buffer out;
    fmt::format_to(fmt::appender(out), "{},{},{},samples", axes[0], axes[1], axes[2]);
    for (const FieldColumn& c : columns)
        for (const std::string& k : c.components)
            fmt::format_to(fmt::appender(out), ",{}{}{}", c.name, k.empty() ? "" : "_", k);
    out.push_back('\n');
    const analysis::CgGrid& g = f.grid;
    std::size_t node = 0;
    for (std::size_t c = 0; c < g.cells[2]; ++c)
        for (std::size_t b = 0; b < g.cells[1]; ++b)
            for (std::size_t a = 0; a < g.cells[0]; ++a, ++node) {
                const Vec3 x = g.node(a, b, c);
                fmt::format_to(fmt::appender(out), "{},{},{},{}", x.x, x.y, x.z, f.samples);
                for (const FieldColumn& column : columns) {
                    const std::size_t n = column.components.size();
                    for (std::size_t k = 0; k < n; ++k)
                        fmt::format_to(fmt::appender(out), ",{}", column.values[n * node + k]);
                }
                out.push_back('\n');
                if (out.size() > (1u << 20)) {  // a block of rows at a time
                    stream.write(out.data(), static_cast<std::streamsize>(out.size()));
                    out.clear();
                }
            }
    stream.write(out.data(), static_cast<std::streamsize>(out.size()));
    check_written(stream, part);
}

}  // namespace

void write_fields_csv(const std::filesystem::path& file, const analysis::Fields& f, const std::string& axes) {
    const std::filesystem::path part = file.string() + ".tmp";
    std::ofstream stream = open_for_writing(part);
    try {
        write_rows(stream, part, f, axes);
    } catch (...) {  // no partial file left behind
        stream.close();
        std::error_code ec;
        std::filesystem::remove(part, ec);
        throw;
    }
    stream.close();
    std::error_code ec;
    std::filesystem::rename(part, file, ec);
    if (ec) throw Error(part.string() + ": cannot rename to " + file.string() + ": " + ec.message());
}

Json drum_frame_json(const analysis::DrumSurface& surface, const analysis::FlowingLayer& layer, double span) {
    constexpr double degrees = 180.0 / pi;
    Json j;
    j["angle_of_repose_deg"] = surface.angle * degrees;
    j["surface_level_m"] = surface.level;
    j["surface_half_length_m"] = surface.half_length;
    j["span"] = span;
    j["bed_solid_fraction"] = surface.solid_fraction;
    j["surface_solid_fraction"] = 0.5 * surface.solid_fraction;
    j["surface_velocity_m_per_s"] = layer.surface_velocity;
    j["layer_thickness_m"] = layer.thickness;  // null where u does not turn
    j["layer_thickness_diameters"] = layer.thickness / layer.diameter;
    j["mean_diameter_m"] = layer.diameter;
    j["fit_columns"] = surface.columns;
    j["fit_iterations"] = surface.iterations;
    return j;
}

}  // namespace tumble::io
