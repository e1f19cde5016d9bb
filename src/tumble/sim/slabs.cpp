// SPDX-License-Identifier: MIT
#include "tumble/sim/slabs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

#include "tumble/core/error.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble {

namespace {

// Tags of the three kinds of exchange, one per direction (+0: upwards, +1: downwards).
constexpr int migrate_tag = 100, ghost_tag = 102, update_tag = 104;

// Plain values into and out of a message.
template <class T>
void put(mpi::Bytes& b, const T& v) {
    const char* c = reinterpret_cast<const char*>(&v);
    b.insert(b.end(), c, c + sizeof(T));
}

class Reader {
public:
    explicit Reader(const mpi::Bytes& b) : b_(b) {}
    template <class T>
    T get() {
        if (at_ + sizeof(T) > b_.size()) throw Error("slabs: a message from another rank is shorter than it says");
        T v;
        std::memcpy(&v, b_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    bool done() const { return at_ == b_.size(); }

private:
    const mpi::Bytes& b_;
    std::size_t at_ = 0;
};

// Every field of sphere i (ParticleStore::fields(), in order).
void put_particle(mpi::Bytes& b, const ParticleStore& p, std::size_t i) {
    std::apply([&](const auto&... field) { (put(b, field[i]), ...); }, p.fields());
}

void get_particle(Reader& r, ParticleStore& p) {
    std::apply([&](auto&... field) { (field.push_back(r.get<typename std::decay_t<decltype(field)>::value_type>()), ...); },
               p.fields());
}

// What a kinematic (wall) sphere costs a rank against a grain, for the
// placement of the cuts: it is moved each step and takes part in the pairs
// of the grains that touch it, but has no pairs of its own kind, no
// integration and no wall contacts. Measured on the long drum (`tumble
// bench --case long-drum` on 2 ranks, halves start: cuts by grains alone
// gave one rank twice the other's wall spheres and the other rank 15 %
// of its time waiting): 0.2.
constexpr double wall_sphere_weight = 0.2;

// The weights of the rebalance, which knows each sphere's pairs: what a
// step costs per grain, per kinematic sphere and per pair, against a grain.
// Measured on the long drum (2026-12-01, Intel Xeon family 6 model 167):
// `perf record` of one process put 334 k cycles per pair over the run in
// the pair loop and 395 k per grain in its search, kicks and drift (pair
// 0.85); `perf record` of each of 2 ranks then fitted the wall sphere: with
// 0.25 (its motion alone) the rank holding 3,402 wall spheres against the
// other's 1,827 spent 7 % more cycles, most of them in the grain-wall pairs
// that read the wall spheres; with 0.85 the ranks were within 2 %. (The
// start's cuts, made before there is a list, weigh a grain with its pairs
// as 1 and a wall sphere as wall_sphere_weight against it.)
constexpr double rebalance_grain_weight = 1.0;
constexpr double rebalance_wall_weight = 0.85;
constexpr double rebalance_pair_weight = 0.85;

// The motion sent each step: position, velocity, spin, half kick.
constexpr std::size_t motion_bytes = 4 * sizeof(Vec3);

// Moves sphere i by `shift` along the axis (a wrap across the period): its
// position, and the wraps a kinematic sphere remembers.
void shift_particle(ParticleStore& p, std::size_t i, int axis, double shift) {
    p.position[i][axis] += shift;
    p.image_shift[i][axis] += shift;
}

}  // namespace

Slabs::Slabs(const Domain& domain, int axis, const ParticleStore& all, double reach)
    : domain_(domain), axis_(axis), reach_(reach), rank_(mpi::rank()), ranks_(mpi::size()) {
    const bool periodic = domain.periodic[axis];
    const double length = domain.hi[axis] - domain.lo[axis];
    // (coordinate, weight) of every sphere, in order along the axis.
    std::vector<std::pair<double, double>> x;
    double total = 0.0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        double v = all.position[i][axis];
        if (periodic) v -= std::floor((v - domain.lo[axis]) / length) * length;
        const double w = all.is_kinematic(i) ? wall_sphere_weight : 1.0;
        x.emplace_back(v, w);
        total += w;
    }
    std::sort(x.begin(), x.end());
    const auto n = static_cast<std::size_t>(ranks_);
    const double infinity = std::numeric_limits<double>::infinity();
    state_.cuts.assign(n + 1, 0.0);
    state_.cuts[0] = periodic ? domain.lo[axis] : -infinity;
    state_.cuts[n] = periodic ? domain.hi[axis] : infinity;
    double below = 0.0;  // the weight of the spheres before x[k]
    std::size_t k = 0;
    for (std::size_t r = 1; r < n; ++r) {  // cut r before the first sphere whose weight below reaches r/n of all
        while (k < x.size() && below + x[k].second <= total * static_cast<double>(r) / static_cast<double>(n))
            below += x[k++].second;
        state_.cuts[r] = x.empty()        ? domain.lo[axis] + length * static_cast<double>(r) / static_cast<double>(n)
                  : k == 0         ? x[0].first
                  : k == x.size() ? x.back().first
                                   : 0.5 * (x[k - 1].first + x[k].first);
    }
    for (std::size_t r = 0; r < n; ++r)
        if (std::isfinite(state_.cuts[r]) && std::isfinite(state_.cuts[r + 1]) && state_.cuts[r + 1] - state_.cuts[r] < reach)
            throw Error("domain decomposition: slab " + std::to_string(r) + " of " + std::to_string(n) + " along " +
                        std::string(1, "xyz"[axis]) + " would be " + std::to_string(state_.cuts[r + 1] - state_.cuts[r]) +
                        " m wide, less than the reach of a contact plus the skin (" + std::to_string(reach) +
                        " m): run on fewer ranks");
    side_[0] = {rank_ > 0 ? rank_ - 1 : periodic ? ranks_ - 1 : mpi::no_rank, rank_ == 0 && periodic ? length : 0.0};
    side_[1] = {rank_ + 1 < ranks_ ? rank_ + 1 : periodic ? 0 : mpi::no_rank,
                rank_ + 1 == ranks_ && periodic ? -length : 0.0};
}

Domain Slabs::local_domain() const {
    Domain d = domain_;
    d.periodic[static_cast<std::size_t>(axis_)] = false;
    return d;
}

void Slabs::keep_own(ParticleStore& p) const {
    const double length = domain_.hi[axis_] - domain_.lo[axis_];
    std::vector<std::uint32_t> own;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (domain_.periodic[axis_])
            shift_particle(p, i, axis_, -std::floor((p.position[i][axis_] - domain_.lo[axis_]) / length) * length);
        const double x = p.position[i][axis_];
        if (x >= lo() && x < hi()) own.push_back(static_cast<std::uint32_t>(i));
    }
    p.keep(own);
}

void Slabs::migrate(ParticleStore& p, std::vector<KeyedHistory>& histories, std::vector<ContactHistory>& wall_history,
                    std::vector<std::uint32_t>& wall_feature, std::size_t wall_slots) {
    ++traffic_.rebuilds;
    std::array<std::vector<std::uint32_t>, 2> leaving;
    std::vector<std::uint32_t> staying;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double x = p.position[i][axis_];
        (x < lo() ? leaving[0] : x >= hi() ? leaving[1] : staying).push_back(static_cast<std::uint32_t>(i));
    }
    // Per side: the spheres (each with its wall histories when there are
    // walls), then the histories of their pairs.
    std::array<mpi::Bytes, 2> out;
    for (int s = 0; s < 2; ++s) {
        mpi::Bytes& b = out[static_cast<std::size_t>(s)];
        const auto& go = leaving[static_cast<std::size_t>(s)];
        std::vector<std::int64_t> ids;
        put(b, go.size());
        for (std::uint32_t i : go) {
            shift_particle(p, i, axis_, side_[static_cast<std::size_t>(s)].shift);
            put_particle(b, p, i);
            ids.push_back(p.id[i]);
            if (!wall_history.empty())
                for (std::size_t slot = 0; slot < wall_slots; ++slot) {
                    put(b, wall_history[wall_slots * static_cast<std::size_t>(p.id[i]) + slot]);
                    put(b, wall_feature[wall_slots * static_cast<std::size_t>(p.id[i]) + slot]);
                }
        }
        std::sort(ids.begin(), ids.end());
        std::vector<KeyedHistory> theirs;
        for (const KeyedHistory& h : histories)
            if (std::binary_search(ids.begin(), ids.end(), h.lo) || std::binary_search(ids.begin(), ids.end(), h.hi))
                theirs.push_back(h);
        put(b, theirs.size());
        for (const KeyedHistory& h : theirs) put(b, h);
    }
    p.keep(staying);
    // Upwards first (each rank sends above, hears from below), then downwards.
    for (int s : {1, 0}) {
        if (side_[static_cast<std::size_t>(s)].rank != mpi::no_rank)
            traffic_.rebuild_bytes += static_cast<std::int64_t>(out[static_cast<std::size_t>(s)].size());
        const mpi::Bytes in = mpi::exchange(side_[static_cast<std::size_t>(s)].rank, out[static_cast<std::size_t>(s)],
                                            side_[static_cast<std::size_t>(1 - s)].rank, migrate_tag + (1 - s));
        if (in.empty()) continue;
        Reader r(in);
        const auto count = r.get<std::size_t>();
        for (std::size_t k = 0; k < count; ++k) {
            get_particle(r, p);
            if (!wall_history.empty())
                for (std::size_t slot = 0; slot < wall_slots; ++slot) {
                    wall_history[wall_slots * static_cast<std::size_t>(p.id.back()) + slot] = r.get<ContactHistory>();
                    wall_feature[wall_slots * static_cast<std::size_t>(p.id.back()) + slot] = r.get<std::uint32_t>();
                }
        }
        const auto arrived = r.get<std::size_t>();
        for (std::size_t k = 0; k < arrived; ++k) histories.push_back(r.get<KeyedHistory>());
        if (!r.done()) throw Error("slabs: a migration message from another rank is longer than it says");
    }
}

void Slabs::make_ghosts(ParticleStore& p) {
    const std::size_t owned = p.size();
    for (auto& list : state_.send) list.clear();
    for (std::size_t i = 0; i < owned; ++i) {
        const double x = p.position[i][axis_];
        if (side_[0].rank != mpi::no_rank && x < lo() + reach_) state_.send[0].push_back(static_cast<std::uint32_t>(i));
        if (side_[1].rank != mpi::no_rank && x >= hi() - reach_) state_.send[1].push_back(static_cast<std::uint32_t>(i));
    }
    for (int s : {1, 0}) {
        const auto& side = side_[static_cast<std::size_t>(s)];
        mpi::Bytes out;
        ParticleStore copy;  // the copy is sent shifted; the sphere itself stays as it is, bit for bit
        for (std::uint32_t i : state_.send[static_cast<std::size_t>(s)]) {
            copy.resize(0);
            copy.append(p, i);
            shift_particle(copy, 0, axis_, side.shift);
            put_particle(out, copy, 0);
        }
        if (side.rank != mpi::no_rank) traffic_.rebuild_bytes += static_cast<std::int64_t>(out.size());
        const mpi::Bytes in =
            mpi::exchange(side.rank, out, side_[static_cast<std::size_t>(1 - s)].rank, ghost_tag + (1 - s));
        const std::size_t from = static_cast<std::size_t>(1 - s);  // received from below in the upward pass
        state_.receive_begin[from] = p.size();
        Reader r(in);
        while (!r.done()) get_particle(r, p);
        state_.receive_count[from] = p.size() - state_.receive_begin[from];
    }
}

// Both directions at once (mpi::exchange_pair): message s goes to side s
// and comes from side 1 - s, whose ghosts this rank holds from the last
// rebuild, so both ends know its size.
void Slabs::update_ghosts(ParticleStore& p, std::size_t owned) {
    ++traffic_.updates;
    std::array<mpi::Bytes, 2> out;
    std::array<int, 2> to{}, from{}, tag{};
    std::array<std::size_t, 2> expected{};
    for (std::size_t s = 0; s < 2; ++s) {
        const auto& side = side_[s];
        out[s].reserve(state_.send[s].size() * motion_bytes);
        for (std::uint32_t i : state_.send[s]) {
            Vec3 x = p.position[i];
            x[axis_] += side.shift;
            put(out[s], x);
            put(out[s], p.velocity[i]);
            put(out[s], p.angular_velocity[i]);
            put(out[s], p.half_kick[i]);
        }
        if (side.rank != mpi::no_rank) traffic_.update_bytes += static_cast<std::int64_t>(out[s].size());
        to[s] = side.rank;
        from[s] = side_[1 - s].rank;
        tag[s] = update_tag + static_cast<int>(1 - s);
        expected[s] = state_.receive_count[1 - s] * motion_bytes;
    }
    const std::array<mpi::Bytes, 2> in = mpi::exchange_pair(to, out, from, expected, tag);
    for (std::size_t s = 0; s < 2; ++s) {
        const std::size_t side = 1 - s;
        const std::size_t begin = state_.receive_begin[side], count = state_.receive_count[side];
        if (in[s].size() != count * motion_bytes || begin + count > p.size())
            throw Error("slabs: the ghosts from rank " + std::to_string(side_[side].rank) +
                        " do not match those of the last rebuild");
        Reader r(in[s]);
        for (std::size_t g = begin; g < begin + count; ++g) {
            p.position[g] = r.get<Vec3>();
            p.velocity[g] = r.get<Vec3>();
            p.angular_velocity[g] = r.get<Vec3>();
            p.half_kick[g] = r.get<Vec3>();
        }
    }
    for (std::size_t g = owned; g < p.size(); ++g) p.force[g] = p.torque[g] = Vec3{};
}

bool Slabs::rebalance(const ParticleStore& p, std::size_t owned, const PairList& pairs) {
    const auto n = static_cast<std::size_t>(ranks_);
    std::vector<double>& cut = state_.cuts;
    // The range of the histogram: the box on a periodic axis, else where the spheres are.
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < owned; ++i) {
        low = std::min(low, p.position[i][axis_]);
        high = std::max(high, p.position[i][axis_]);
    }
    low = domain_.periodic[axis_] ? domain_.lo[axis_] : -mpi::max(-low);
    high = domain_.periodic[axis_] ? domain_.hi[axis_] : mpi::max(high);
    constexpr std::size_t bins = 1024;
    const double width = (high - low) / static_cast<double>(bins);
    if (!(width > 0.0)) return false;
    // Whole counts per bin, of grains, kinematic spheres and pairs (at their
    // first sphere): their sums over the ranks are exact, whatever the
    // order of the additions.
    std::vector<double> count(3 * bins, 0.0);
    std::vector<std::size_t> bin_of(owned);
    for (std::size_t i = 0; i < owned; ++i) {
        const double x = (p.position[i][axis_] - low) / width;
        bin_of[i] = static_cast<std::size_t>(std::clamp(x, 0.0, static_cast<double>(bins - 1)));
        count[3 * bin_of[i] + (p.is_kinematic(i) ? 1 : 0)] += 1.0;
    }
    for (const std::uint32_t i : pairs.first) count[3 * bin_of[i] + 2] += 1.0;
    const auto weigh = [](const double* c) {
        return rebalance_grain_weight * c[0] + rebalance_wall_weight * c[1] + rebalance_pair_weight * c[2];
    };
    double mine = 0.0;
    for (std::size_t b = 0; b < bins; ++b) mine += weigh(&count[3 * b]);
    mpi::sum(count);
    std::vector<double> weight(bins);
    double total = 0.0;
    for (std::size_t b = 0; b < bins; ++b) total += weight[b] = weigh(&count[3 * b]);
    if (mpi::max(mine) <= 1.02 * total / static_cast<double>(n)) return false;
    std::vector<double> wanted = cut;
    double below = 0.0;
    std::size_t b = 0;
    for (std::size_t r = 1; r < n; ++r) {  // where the weight below reaches r/n of all, within its bin by proportion
        const double target = total * static_cast<double>(r) / static_cast<double>(n);
        while (b + 1 < bins && below + weight[b] < target) below += weight[b++];
        const double within = weight[b] > 0.0 ? std::clamp((target - below) / weight[b], 0.0, 1.0) : 0.0;
        wanted[r] = low + (static_cast<double>(b) + within) * width;
    }
    bool moved = false;
    for (std::size_t r = 1; r < n; ++r) {  // in order: each slab's lower cut is already final
        const double left = cut[r] - cut[r - 1], right = cut[r + 1] - cut[r];
        const double step = 0.5 * std::min(std::isfinite(left) ? left : right, std::isfinite(right) ? right : left);
        const double to = std::clamp(wanted[r], cut[r] - step, cut[r] + step);
        if (to - cut[r - 1] < reach_ || cut[r + 1] - to < reach_) continue;  // a slab too narrow: this cut stays
        moved = moved || to != cut[r];
        cut[r] = to;
    }
    return moved;
}

ParticleStore Slabs::gather_own(const ParticleStore& p, std::size_t owned, const std::function<bool(std::size_t)>& which,
                                Everywhere everywhere) const {
    mpi::Bytes mine;
    for (std::size_t i = 0; i < owned; ++i)
        if (!which || which(i)) put_particle(mine, p, i);
    ParticleStore all;
    for (const mpi::Bytes& part : everywhere == Everywhere::yes ? mpi::all_gather(mine) : mpi::gather(mine)) {
        Reader r(part);
        while (!r.done()) get_particle(r, all);
    }
    std::vector<std::uint32_t> order(all.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return all.id[a] < all.id[b]; });
    all.permute(order);
    return all;
}

}  // namespace tumble
