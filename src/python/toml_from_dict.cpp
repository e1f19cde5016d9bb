// SPDX-License-Identifier: MIT
// A Python dict as the TOML table the readers take (bindings.hpp).
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "io/config.hpp"
#include "io/toml_reader.hpp"

namespace tumble::python {

namespace {

toml::table table_of(const py::handle& d, const std::filesystem::path& name, const std::string& path);
toml::array array_of_items(const py::handle& items, const std::filesystem::path& name, const std::string& path);

// Hands `value` as a TOML value to put(); `path` names it in messages
// (config.hpp's convention).
template <class Put>
void convert(const py::handle& value, const std::filesystem::path& name, const std::string& path, Put&& put) {
    const py::module_ numpy = py::module_::import("numpy");
    if (py::isinstance<py::bool_>(value) || py::isinstance(value, numpy.attr("bool_"))) {
        put(value.cast<bool>());
    } else if (py::isinstance<py::int_>(value) || py::isinstance(value, numpy.attr("integer"))) {
        put(value.cast<std::int64_t>());
    } else if (py::isinstance<py::float_>(value) || py::isinstance(value, numpy.attr("floating"))) {
        put(value.cast<double>());
    } else if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) {
        put(py::module_::import("os").attr("fspath")(value).cast<std::string>());
    } else if (py::isinstance<py::dict>(value)) {
        put(table_of(value, name, path));
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
               py::isinstance<py::array>(value)) {
        put(array_of_items(py::isinstance<py::array>(value) ? value.attr("tolist")() : value, name, path));
    } else {
        throw io::ConfigError(name, path, "cannot be given in TOML: a " +
                                              py::type::of(value).attr("__name__").cast<std::string>());
    }
}

toml::array array_of_items(const py::handle& items, const std::filesystem::path& name, const std::string& path) {
    toml::array array;
    std::size_t k = 0;
    for (const py::handle item : items)
        convert(item, name, io::at(path, k++), [&](auto&& v) { array.push_back(std::move(v)); });
    return array;
}

toml::table table_of(const py::handle& d, const std::filesystem::path& name, const std::string& path) {
    toml::table table;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(d)) {
        if (!py::isinstance<py::str>(key)) throw io::ConfigError(name, path, "keys must be strings");
        const std::string k = key.cast<std::string>();
        convert(value, name, io::join(path, k), [&](auto&& v) { table.insert_or_assign(k, std::move(v)); });
    }
    return table;
}

}  // namespace

toml::table toml_from_dict(const py::dict& d, const std::filesystem::path& name) { return table_of(d, name, ""); }

}  // namespace tumble::python
