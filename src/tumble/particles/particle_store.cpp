// SPDX-License-Identifier: MIT
#include "tumble/particles/particle_store.hpp"

#include <utility>

namespace tumble {

namespace {
// f(a_k, b_k) for the k-th field of two stores.
template <class A, class B, class F>
void each_field_pair(A& a, B& b, F&& f) {
    std::apply([&](auto&... to) { std::apply([&](auto&... from) { (f(to, from), ...); }, b.fields()); }, a.fields());
}
}  // namespace

void ParticleStore::gather(const ParticleStore& from, const std::vector<std::uint32_t>& order, IndexRange r) {
    each_field_pair(*this, from, [&](auto& to, const auto& source) {
        for (std::size_t k = r.begin; k < r.end; ++k) to[k] = source[order[k]];
    });
}

void ParticleStore::resize(std::size_t n) {
    std::apply([&](auto&... field) { (field.resize(n), ...); }, fields());
}

void ParticleStore::reserve(std::size_t n) {
    std::apply([&](auto&... field) { (field.reserve(n), ...); }, fields());
}

void ParticleStore::keep(const std::vector<std::uint32_t>& indices) {
    // In place: indices[k] >= k, so no field value is overwritten before it is read.
    std::apply(
        [&](auto&... field) {
            auto keep_field = [&](auto& f) {
                for (std::size_t k = 0; k < indices.size(); ++k) f[k] = f[indices[k]];
                f.resize(indices.size());
            };
            (keep_field(field), ...);
        },
        fields());
}

void ParticleStore::append(const ParticleStore& from, std::size_t i) {
    each_field_pair(*this, from, [&](auto& to, const auto& source) { to.push_back(source[i]); });
}

void ParticleStore::permute(const std::vector<std::uint32_t>& order) {
    ParticleStore sorted = *this;
    sorted.gather(*this, order, {0, size()});
    *this = std::move(sorted);
}

}  // namespace tumble
