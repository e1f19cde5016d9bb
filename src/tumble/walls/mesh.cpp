// SPDX-License-Identifier: MIT
#include "tumble/walls/mesh.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>

#include "tumble/core/constants.hpp"

namespace tumble {

namespace {

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

std::string point(const Vec3& p) { return "(" + number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")"; }

bool finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Twice the area, |(b - a) x (c - a)|, m^2, and the longest edge squared, m^2.
struct TriangleSize {
    double twice_area, longest2;
};

TriangleSize triangle_size(const Vec3& a, const Vec3& b, const Vec3& c) {
    return {norm(cross(b - a, c - a)), std::max({norm2(b - a), norm2(c - b), norm2(a - c)})};
}

// The checks of one triangle's corners, shared by check_mesh and set_vertices.
void check_corners(std::size_t t, const std::array<Vec3, 3>& x) {
    for (int j = 0; j < 3; ++j)
        if (!finite(x[j])) throw MeshError(t, "corner " + std::to_string(j + 1) + " is not finite: " + point(x[j]));
    if (is_degenerate_triangle(x[0], x[1], x[2])) {
        const TriangleSize size = triangle_size(x[0], x[1], x[2]);
        throw MeshError(t, "degenerate: its area, " + number(0.5 * size.twice_area) +
                               " m^2, is not above 1e-12 times its longest edge squared, " + number(size.longest2) +
                               " m^2 (corners " + point(x[0]) + ", " + point(x[1]) + ", " + point(x[2]) + ")");
    }
}

// Counting sort of (key, value) pairs into compressed rows: row k holds the
// values of key k, in the order given. `start` gets keys + 1 entries.
template <class Pairs>
void compressed_rows(std::size_t keys, const Pairs& pairs, std::vector<std::uint32_t>& start,
                     std::vector<std::uint32_t>& values) {
    start.assign(keys + 1, 0);
    for (const auto& [key, value] : pairs) ++start[key + 1];
    for (std::size_t k = 0; k < keys; ++k) start[k + 1] += start[k];
    values.resize(start[keys]);
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (const auto& [key, value] : pairs) values[next[key]++] = value;
}

}  // namespace

MeshError::MeshError(std::size_t triangle, std::string reason)
    : Error("triangle " + std::to_string(triangle + 1) + ": " + reason),
      triangle_(triangle),
      reason_(std::move(reason)) {}

TriangleMesh weld_triangles(std::span<const std::array<Vec3, 3>> corners) {
    // Key: the bits of the three coordinates, -0 made +0 by adding +0.
    struct Key {
        std::array<std::uint64_t, 3> bits;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 0x9e3779b97f4a7c15ULL;
            for (std::uint64_t b : k.bits) h = (h ^ b) * 0xbf58476d1ce4e5b9ULL, h ^= h >> 31;
            return static_cast<std::size_t>(h);
        }
    };
    TriangleMesh mesh;
    mesh.triangles.reserve(corners.size());
    std::unordered_map<Key, std::uint32_t, Hash> ids;
    ids.reserve(corners.size() * 3 / 2);
    for (const std::array<Vec3, 3>& triangle : corners) {
        std::array<std::uint32_t, 3> t{};
        for (int j = 0; j < 3; ++j) {
            const Vec3& p = triangle[j];
            const Key key{{std::bit_cast<std::uint64_t>(p.x + 0.0), std::bit_cast<std::uint64_t>(p.y + 0.0),
                           std::bit_cast<std::uint64_t>(p.z + 0.0)}};
            const auto [at, added] = ids.try_emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
            if (added) mesh.vertices.push_back(p);
            t[j] = at->second;
        }
        mesh.triangles.push_back(t);
    }
    return mesh;
}

bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    const TriangleSize size = triangle_size(a, b, c);
    return !(0.5 * size.twice_area > 1e-12 * size.longest2);
}

void check_mesh(const TriangleMesh& mesh) {
    if (mesh.triangles.empty()) throw Error("the mesh has no triangles");
    // Ids are 32-bit, a face's sides 3 f + k.
    if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max() ||
        mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3)
        throw Error("the mesh has " + std::to_string(mesh.vertices.size()) + " vertices and " +
                    std::to_string(mesh.triangles.size()) + " triangles, more than its ids can number");
    const std::size_t n = mesh.vertices.size();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& v = mesh.triangles[t];
        for (int j = 0; j < 3; ++j)
            if (v[j] >= n)
                throw MeshError(t, "vertex id " + std::to_string(v[j]) + " is out of range (the mesh has " +
                                       std::to_string(n) + " vertices)");
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
            throw MeshError(t, "uses a vertex twice (vertex ids " + std::to_string(v[0]) + ", " +
                                   std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")");
        check_corners(t, {mesh.vertices[v[0]], mesh.vertices[v[1]], mesh.vertices[v[2]]});
    }
    // A triangle repeated: the vertex-id triples (ids sorted within each)
    // sorted with their indices, so each run of one triple starts with its
    // first triangle; the earliest second copy in the mesh's order is named.
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::size_t>> sorted(mesh.triangles.size());
    for (std::size_t t = 0; t < sorted.size(); ++t) {
        sorted[t] = {mesh.triangles[t], t};
        std::sort(sorted[t].first.begin(), sorted[t].first.end());
    }
    std::sort(sorted.begin(), sorted.end());
    std::size_t copy = sorted.size(), original = 0;
    for (std::size_t k = 1; k < sorted.size(); ++k)
        if (sorted[k].first == sorted[k - 1].first && (k == 1 || sorted[k - 1].first != sorted[k - 2].first) &&
            sorted[k].second < copy)
            copy = sorted[k].second, original = sorted[k - 1].second;
    if (copy < sorted.size())
        throw MeshError(copy, "repeats triangle " + std::to_string(original + 1) +
                                  " (the same three vertices): its forces would count twice");
}

MeshTopology::MeshTopology(TriangleMesh mesh) {
    check_mesh(mesh);
    vertices_ = std::move(mesh.vertices);
    triangles_ = std::move(mesh.triangles);
    const std::size_t faces = triangles_.size();

    // Edges: every side as (lower id, higher id, 3 f + k), sorted; each run of
    // one vertex pair is one edge, its sides in face order.
    struct Side {
        std::uint32_t lo, hi, side;
        bool operator<(const Side& o) const {
            return lo != o.lo ? lo < o.lo : (hi != o.hi ? hi < o.hi : side < o.side);
        }
    };
    std::vector<Side> sides(3 * faces);
    for (std::size_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = triangles_[f][k], b = triangles_[f][(k + 1) % 3];
            sides[3 * f + k] = {std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(3 * f + k)};
        }
    std::sort(sides.begin(), sides.end());
    face_edges_.resize(faces);
    edge_side_start_.clear();
    edge_sides_.clear();
    for (std::size_t i = 0; i < sides.size(); ++i) {
        if (i == 0 || sides[i].lo != sides[i - 1].lo || sides[i].hi != sides[i - 1].hi) {
            edge_side_start_.push_back(static_cast<std::uint32_t>(i));
            edges_.push_back({sides[i].lo, sides[i].hi});
        }
        edge_sides_.push_back(sides[i].side);
        face_edges_[sides[i].side / 3][sides[i].side % 3] = static_cast<std::uint32_t>(edges_.size() - 1);
    }
    edge_side_start_.push_back(static_cast<std::uint32_t>(sides.size()));

    std::vector<std::pair<std::uint32_t, std::uint32_t>> incidence;  // (vertex, face or edge)
    incidence.reserve(3 * faces);
    for (std::size_t f = 0; f < faces; ++f)
        for (std::uint32_t v : triangles_[f]) incidence.emplace_back(v, static_cast<std::uint32_t>(f));
    compressed_rows(vertices_.size(), incidence, vertex_face_start_, vertex_faces_);
    incidence.clear();
    for (std::size_t e = 0; e < edges_.size(); ++e)
        for (std::uint32_t v : edges_[e]) incidence.emplace_back(v, static_cast<std::uint32_t>(e));
    compressed_rows(vertices_.size(), incidence, vertex_edge_start_, vertex_edges_);

    update_geometry();
}

void MeshTopology::set_vertices(std::span<const Vec3> vertices) {
    if (vertices.size() != vertices_.size())
        throw Error("mesh: set_vertices got " + std::to_string(vertices.size()) + " vertices for a mesh of " +
                    std::to_string(vertices_.size()));
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
        const auto& v = triangles_[t];
        check_corners(t, {vertices[v[0]], vertices[v[1]], vertices[v[2]]});
    }
    std::copy(vertices.begin(), vertices.end(), vertices_.begin());
    update_geometry();
}

void MeshTopology::update_geometry() {
    faces_.resize(triangles_.size());
    for (std::size_t f = 0; f < triangles_.size(); ++f) {
        FaceGeometry& g = faces_[f];
        const auto& v = triangles_[f];
        for (int j = 0; j < 3; ++j) g.corner[j] = vertices_[v[j]];
        const Vec3 area = cross(g.corner[1] - g.corner[0], g.corner[2] - g.corner[0]);
        const double length = norm(area);
        g.normal = {area.x / length, area.y / length, area.z / length};
        for (int k = 0; k < 3; ++k) {
            // m_k = unit (x_k+1 - x_k) x N: for counter-clockwise corners seen
            // from the side N points to, the side turned clockwise, outwards.
            const Vec3 out = cross(g.corner[(k + 1) % 3] - g.corner[k], g.normal);
            const double l = norm(out);
            g.side_normal[k] = {out.x / l, out.y / l, out.z / l};
            g.side_origin[k] = static_cast<std::uint8_t>(v[k] < v[(k + 1) % 3] ? k : (k + 1) % 3);
        }
    }
    // Flat: two faces whose normals are parallel within 1e-12 rad
    // (|N_f x N_g| = sin of the angle) and which lie on either side of the
    // edge (m . m' < 0; a sheet folded back onto itself has m = m').
    auto parallel = [&](std::uint32_t f, std::uint32_t g) {
        return norm(cross(faces_[f].normal, faces_[g].normal)) <= 1e-12;
    };
    edge_geometry_.resize(edges_.size());
    for (std::size_t e = 0; e < edges_.size(); ++e) {
        EdgeGeometry& g = edge_geometry_[e];
        g.origin = vertices_[edges_[e][0]];
        g.direction = vertices_[edges_[e][1]] - g.origin;
        g.length2 = norm2(g.direction);
        const std::span<const std::uint32_t> sides = edge_sides(static_cast<std::uint32_t>(e));
        const bool flat = sides.size() == 2 && parallel(sides[0] / 3, sides[1] / 3) &&
                          dot(faces_[sides[0] / 3].side_normal[sides[0] % 3],
                              faces_[sides[1] / 3].side_normal[sides[1] % 3]) < 0.0;
        g.plane = flat ? sides[0] / 3 : no_face;
    }
    // A flat vertex: every edge at it flat, every face at it parallel to the first.
    vertex_plane_.assign(vertices_.size(), no_face);
    for (std::uint32_t v = 0; v < vertices_.size(); ++v) {
        const std::span<const std::uint32_t> faces = vertex_faces(v), edges = vertex_edges(v);
        const bool flat =
            !faces.empty() &&
            std::all_of(edges.begin(), edges.end(), [&](std::uint32_t e) { return edge_geometry_[e].plane != no_face; }) &&
            std::all_of(faces.begin(), faces.end(), [&](std::uint32_t f) { return parallel(faces[0], f); });
        if (flat) vertex_plane_[v] = faces[0];
    }
}

namespace {

bool has(const std::vector<MeshContact>& kept, MeshFeature feature, std::uint32_t id) {
    for (const MeshContact& k : kept)
        if (k.feature == feature && k.id == id) return true;
    return false;
}

// Rule 4: a point within `same` of a kept contact's.
bool coincides(const Vec3& q, std::span<const MeshContact> kept, double same) {
    for (const MeshContact& k : kept)
        if (norm2(k.point - q) <= same * same) return true;
    return false;
}

// Where c lies relative to a face: d = (c - x_0) . N, m (signed, along N);
// s_k for its three sides and the largest, m. Every point of the face is at
// least sqrt(d^2 + s_k^2) from c for each side with s_k > 0 (the face lies
// behind that side's line, which is s_k from c's projection in the plane).
struct FaceTest {
    double d;
    std::array<double, 3> s;
    double s_max;
};

// d = (c - x_0) . N, m.
double plane_distance(const FaceGeometry& g, const Vec3& c) { return dot(c - g.corner[0], g.normal); }

// The test with d already known (plane_distance()).
FaceTest test_face(const FaceGeometry& g, const Vec3& c, double d) {
    const std::array<double, 3> s{g.side_distance(0, c), g.side_distance(1, c), g.side_distance(2, c)};
    return {d, s, std::max({s[0], s[1], s[2]})};
}

FaceTest test_face(const FaceGeometry& g, const Vec3& c) { return test_face(g, c, plane_distance(g, c)); }

// The contact with face f's plane: n = sign(d) N, q = c - d N, h = R - |d|
// (h <= 0: out of reach). Also the contact of a flat edge or vertex.
MeshContact plane_contact(const MeshTopology& mesh, MeshFeature feature, std::uint32_t id, std::uint32_t f,
                          const Vec3& c, double R) {
    const FaceGeometry& g = mesh.face(f);
    const double d = plane_distance(g, c);
    return {feature, id, c - d * g.normal, d >= 0.0 ? g.normal : -g.normal, R - std::abs(d)};
}

// The contact of an edge or vertex whose closest point is q, r = c - q,
// |r|^2 = distance2 > 0: n = r / |r| (each component divided, so that r along
// an axis gives that axis exactly), h = R - |r|; a flat one's from its plane.
MeshContact feature_contact(const MeshTopology& mesh, MeshFeature feature, std::uint32_t id, const Vec3& c, double R,
                            const Vec3& q, const Vec3& r, double distance2) {
    const std::uint32_t plane = feature == MeshFeature::edge ? mesh.edge(id).plane : mesh.vertex_plane(id);
    if (plane != no_face) return plane_contact(mesh, feature, id, plane, c, R);
    const double distance = std::sqrt(distance2);
    return {feature, id, q, {r.x / distance, r.y / distance, r.z / distance}, R - distance};
}

// tau = (c - x_0e) . (x_1e - x_0e), m^2: the edge's interior is nearest c
// where 0 < tau < |edge|^2, its origin where tau <= 0, its other end where
// tau >= |edge|^2. The edge's test and its ends' tests read these same numbers.
double projection(const EdgeGeometry& g, const Vec3& c) { return dot(c - g.origin, g.direction); }

bool interior(const EdgeGeometry& g, double tau) { return tau > 0.0 && tau < g.length2; }

// The point of edge e nearest c, as the vertex at an end when that is nearest.
struct Nearest {
    MeshFeature feature;
    std::uint32_t id;
    Vec3 q, r;  // the point, m; c - q, m
    double distance2;
};

// The interior point of edge e nearest c, given its tau with 0 < tau < |edge|^2.
Nearest inside_edge(const MeshTopology& mesh, std::uint32_t e, const Vec3& c, double tau) {
    const EdgeGeometry& g = mesh.edge(e);
    const double t = tau / g.length2;
    // r = w - t (x_1e - x_0e), w = c - x_0e, perpendicular to the edge; its
    // rounding along the edge (an ulp of w) removed once more, so that
    // n = r / |r| is perpendicular to the edge to round-off of r itself, even
    // where |r| is far smaller than |w|.
    Vec3 r = (c - g.origin) - t * g.direction;
    r -= (dot(r, g.direction) / g.length2) * g.direction;
    return {MeshFeature::edge, e, g.origin + t * g.direction, r, norm2(r)};
}

Nearest nearest_on_edge(const MeshTopology& mesh, std::uint32_t e, const Vec3& c) {
    const EdgeGeometry& g = mesh.edge(e);
    const double tau = projection(g, c);
    if (interior(g, tau)) return inside_edge(mesh, e, c, tau);
    const std::uint32_t v = mesh.edges()[e][tau > 0.0 ? 1 : 0];
    const Vec3 x = mesh.vertices()[v];
    return {MeshFeature::vertex, v, x, c - x, norm2(c - x)};
}

// Rule 2: the contact of edge e, if its closest point lies inside it, within
// R, and c lies beyond its side in every face of the edge.
bool edge_contact(const MeshTopology& mesh, std::uint32_t e, const Vec3& c, double R, MeshContact& k) {
    const double tau = projection(mesh.edge(e), c);
    if (!interior(mesh.edge(e), tau)) return false;
    for (std::uint32_t side : mesh.edge_sides(e))
        if (mesh.face(side / 3).side_distance(static_cast<int>(side % 3), c) < 0.0) return false;
    const Nearest p = inside_edge(mesh, e, c, tau);
    if (!(p.distance2 < R * R) || p.distance2 == 0.0) return false;
    k = feature_contact(mesh, MeshFeature::edge, e, c, R, p.q, p.r, p.distance2);
    return k.overlap > 0.0;
}

// Rule 3, the vertex's own part: the contact of vertex v, if within R and
// beyond v on every edge at it (the end of each edge at v is nearest c:
// tau <= 0 where v is the origin, tau >= |edge|^2 where it is the other end).
bool vertex_contact(const MeshTopology& mesh, std::uint32_t v, const Vec3& c, double R, MeshContact& k) {
    const Vec3 x = mesh.vertices()[v];
    const Vec3 r = c - x;
    const double distance2 = norm2(r);
    if (!(distance2 < R * R) || distance2 == 0.0) return false;
    for (std::uint32_t e : mesh.vertex_edges(v)) {
        const EdgeGeometry& g = mesh.edge(e);
        const double tau = projection(g, c);
        if (interior(g, tau) || (mesh.edges()[e][0] == v) != !(tau > 0.0)) return false;
    }
    k = feature_contact(mesh, MeshFeature::vertex, v, c, R, x, r, distance2);
    return k.overlap > 0.0;
}

// Rule 3, the rest: a face or edge at vertex v among the contacts.
bool at_vertex(const MeshTopology& mesh, std::uint32_t v, std::span<const MeshContact> kept) {
    for (const MeshContact& k : kept) {
        if (k.feature == MeshFeature::vertex) continue;
        const std::span<const std::uint32_t> ids =
            k.feature == MeshFeature::face ? std::span<const std::uint32_t>(mesh.triangles()[k.id])
                                           : std::span<const std::uint32_t>(mesh.edges()[k.id]);
        if (std::find(ids.begin(), ids.end(), v) != ids.end()) return true;
    }
    return false;
}

// Rule 5: the point of the candidate faces nearest c, if within R: each
// face's own closest point, the projection when c projects into it, else
// the nearest point of its three sides.
void add_nearest(const MeshTopology& mesh, const Vec3& c, double R, std::span<const std::uint32_t> candidate_faces,
                 std::vector<MeshContact>& out) {
    Nearest best{MeshFeature::face, no_face, {}, {}, R * R};
    for (std::uint32_t f : candidate_faces) {
        const FaceTest t = test_face(mesh.face(f), c);
        if (!(t.d * t.d + std::max(t.s_max, 0.0) * std::max(t.s_max, 0.0) < best.distance2)) continue;
        if (t.s_max < 0.0) {
            best = {MeshFeature::face, f, {}, {}, t.d * t.d};
            continue;
        }
        for (std::uint32_t e : mesh.face_edges()[f]) {
            const Nearest p = nearest_on_edge(mesh, e, c);
            if (p.distance2 < best.distance2 && p.distance2 > 0.0) best = p;
        }
    }
    if (best.id == no_face) return;
    const MeshContact k = best.feature == MeshFeature::face
                              ? plane_contact(mesh, MeshFeature::face, best.id, best.id, c, R)
                              : feature_contact(mesh, best.feature, best.id, c, R, best.q, best.r, best.distance2);
    if (k.overlap > 0.0) out.push_back(k);
}

}  // namespace

void mesh_contacts(const MeshTopology& mesh, const Vec3& c, double R, std::span<const std::uint32_t> candidate_faces,
                   std::vector<MeshContact>& out) {
    out.clear();
    const double R2 = R * R;
    // The contacts each feature gives on its own (rules 1, 2 and the
    // vertex's part of 3), one pass over the faces, kept in out as faces,
    // then edges, then vertices (each in the order found).
    std::size_t faces_end = 0, edges_end = 0;
    bool near = false;  // a face's edges or corners within R: rule 5 may find a contact
    MeshContact k;
    for (std::uint32_t f : candidate_faces) {
        // A face whose plane lies R or more from c (by both tests below) gives
        // nothing: most faces near a sphere, its sides' distances not worked out.
        const FaceGeometry& g = mesh.face(f);
        const double d = plane_distance(g, c);
        if (!(std::abs(d) < R) && !(d * d < R2)) continue;
        const FaceTest t = test_face(g, c, d);
        // Rule 1: c projects into the face, its plane within R.
        if (t.s_max < 0.0) {
            if (std::abs(t.d) < R) {
                out.insert(out.begin() + static_cast<std::ptrdiff_t>(faces_end++),
                           plane_contact(mesh, MeshFeature::face, f, f, c, R));
                ++edges_end;
            }
            continue;
        }
        // Else only the face's edges and corners can touch, if the face comes
        // within R at all (d^2 + s_max^2 < R^2).
        if (!(t.d * t.d + t.s_max * t.s_max < R2)) continue;
        near = true;
        // Rule 2: the edges of the sides c lies beyond (where s < 0 the edge
        // fails its test in this face anyway), within R.
        for (int side = 0; side < 3; ++side) {
            const std::uint32_t e = mesh.face_edges()[f][side];
            if (t.s[side] >= 0.0 && t.d * t.d + t.s[side] * t.s[side] < R2 && !has(out, MeshFeature::edge, e) &&
                edge_contact(mesh, e, c, R, k))
                out.insert(out.begin() + static_cast<std::ptrdiff_t>(edges_end++), k);
        }
        // Rule 3: the corners at a side c lies beyond (a centre beyond a corner
        // on every edge at it lies beyond one of the face's two sides there:
        // the header's argument). The sides at corner j: side j (from it) and
        // side j - 1 (to it).
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t v = mesh.triangles()[f][j];
            if ((t.s[j] >= 0.0 || t.s[(j + 2) % 3] >= 0.0) && !has(out, MeshFeature::vertex, v) &&
                vertex_contact(mesh, v, c, R, k))
                out.push_back(k);
        }
    }
    // Rules 3 and 4 in that order: a vertex with a face or edge at it among the
    // contacts kept, a point that coincides with one kept.
    const double same = 1e-9 * (R + std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}));
    std::size_t kept = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::span<const MeshContact> before(out.data(), kept);
        if ((out[i].feature == MeshFeature::vertex && at_vertex(mesh, out[i].id, before)) ||
            coincides(out[i].point, before, same))
            continue;
        out[kept++] = out[i];
    }
    out.resize(kept);
    // (Rule 5 looks for a face within R as the loop above: none, no contact.)
    if (out.empty() && near) add_nearest(mesh, c, R, candidate_faces, out);
}

void faces_within(const MeshTopology& mesh, const Vec3& c, double reach, std::span<const std::uint32_t> candidate_faces,
                  std::vector<std::uint32_t>& out) {
    for (std::uint32_t f : candidate_faces) {
        const FaceTest t = test_face(mesh.face(f), c);
        const double beyond = std::max(t.s_max, 0.0);  // m
        if (t.d * t.d + beyond * beyond < reach * reach) out.push_back(f);
    }
}

std::string closed_surface_problem(const MeshTopology& mesh) {
    const auto edges = mesh.edges();
    for (std::uint32_t e = 0; e < edges.size(); ++e) {
        const auto sides = mesh.edge_sides(e);
        const std::string where = "the edge between vertices " + std::to_string(edges[e][0] + 1) + " and " +
                                  std::to_string(edges[e][1] + 1);
        if (sides.size() != 2)
            return where + " has " + std::to_string(sides.size()) + (sides.size() == 1 ? " face" : " faces") +
                   ", not two: the mesh is not a closed surface";
        // The side k of face f runs from its corner k to corner k + 1.
        const auto runs_up = [&](std::uint32_t side) {
            const auto& t = mesh.triangles()[side / 3];
            return t[side % 3] < t[(side % 3 + 1) % 3];
        };
        if (runs_up(sides[0]) == runs_up(sides[1]))
            return where + ": triangles " + std::to_string(sides[0] / 3 + 1) + " and " + std::to_string(sides[1] / 3 + 1) +
                   " run along it the same way, so their normals point to opposite sides of the surface";
    }
    return {};
}

double winding_number(const MeshTopology& mesh, const Vec3& x) {
    const auto vertices = mesh.vertices();
    double sum = 0.0;
    for (const auto& t : mesh.triangles()) {
        const Vec3 a = vertices[t[0]] - x, b = vertices[t[1]] - x, c = vertices[t[2]] - x;
        const double la = norm(a), lb = norm(b), lc = norm(c);
        const double numerator = dot(a, cross(b, c));
        const double denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
        sum += 2.0 * std::atan2(numerator, denominator);
    }
    return sum / (4.0 * pi);
}

}  // namespace tumble
