// SPDX-License-Identifier: MIT
// A Python dict as the TOML table the readers take (bindings.hpp).
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "io/config.hpp"
#include "io/toml_reader.hpp"

namespace tumble::python {

namespace {

// Deeper than any scenario or drum file nests (3 levels at most): a dict or
// list that holds itself, or one built by mistake, is refused here rather
// than recursed into until the stack runs out.
constexpr int max_depth = 32;

toml::table table_of(const py::handle& d, const std::filesystem::path& name, const std::string& path, int depth);
toml::array array_of_items(const py::handle& items, const std::filesystem::path& name, const std::string& path,
                           int depth);

// An integer, or the TOML reader's refusal of one that 64 bits cannot hold.
std::int64_t integer_of(const py::handle& value, const std::filesystem::path& name, const std::string& path) {
    const py::int_ number(py::reinterpret_borrow<py::object>(value));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
    if (overflow != 0) {
        const std::string digits = py::str(static_cast<py::handle>(number)).cast<std::string>();
        throw io::ConfigError(name, path, "'" + digits + "' is not representable in 64 bits");
    }
    if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
    return v;
}

// Hands `value` as a TOML value to put(); `path` names it in messages
// (config.hpp's convention); `depth`: the tables and arrays it lies in.
template <class Put>
void convert(const py::handle& value, const std::filesystem::path& name, const std::string& path, int depth,
             Put&& put) {
    const py::module_ numpy = py::module_::import("numpy");
    if (depth > max_depth)
        throw io::ConfigError(name, path, "nested more than " + std::to_string(max_depth) +
                                              " deep (a dict or list that holds itself?)");
    if (py::isinstance<py::bool_>(value) || py::isinstance(value, numpy.attr("bool_"))) {
        put(value.cast<bool>());
    } else if (py::isinstance<py::int_>(value) || py::isinstance(value, numpy.attr("integer"))) {
        put(integer_of(value, name, path));
    } else if (py::isinstance<py::float_>(value) || py::isinstance(value, numpy.attr("floating"))) {
        put(value.cast<double>());
    } else if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) {
        put(py::module_::import("os").attr("fspath")(value).cast<std::string>());
    } else if (py::isinstance<py::dict>(value)) {
        put(table_of(value, name, path, depth + 1));
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
               py::isinstance<py::array>(value)) {
        put(array_of_items(py::isinstance<py::array>(value) ? value.attr("tolist")() : value, name, path, depth + 1));
    } else {
        throw io::ConfigError(name, path, "cannot be given in TOML: a " +
                                              py::type::of(value).attr("__name__").cast<std::string>());
    }
}

toml::array array_of_items(const py::handle& items, const std::filesystem::path& name, const std::string& path,
                           int depth) {
    toml::array array;
    std::size_t k = 0;
    for (const py::handle item : items)
        convert(item, name, io::at(path, k++), depth, [&](auto&& v) { array.push_back(std::move(v)); });
    return array;
}

toml::table table_of(const py::handle& d, const std::filesystem::path& name, const std::string& path, int depth) {
    toml::table table;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(d)) {
        if (!py::isinstance<py::str>(key)) throw io::ConfigError(name, path, "keys must be strings");
        const std::string k = key.cast<std::string>();
        convert(value, name, io::join(path, k), depth, [&](auto&& v) { table.insert_or_assign(k, std::move(v)); });
    }
    return table;
}

}  // namespace

toml::table toml_from_dict(const py::dict& d, const std::filesystem::path& name) {
    return table_of(d, name, "", 1);
}

}  // namespace tumble::python
