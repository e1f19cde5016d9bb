// SPDX-License-Identifier: MIT
// Walls made of triangles (equipment from STL files: hoppers, drums with
// lifters, chutes): the mesh, its topology, and the contacts of one sphere
// with it. Stateless functions in the manner of contact/geometry.hpp; the
// caller owns the contact history (see "History" below).
//
// The mesh. Vertices in m; each triangle lists three vertex ids, and its
// unit normal N follows the right-hand rule of that order. The contact is
// two-sided: a sphere on either side of a face is pushed away from it, so
// N only names a side (open sheets such as chutes need both). Vertices are
// shared between triangles (weld_triangles joins identical coordinates), so
// the mesh has edges with their faces and vertices with their edges and
// faces. An edge may have one face (an open edge: the lip of a chute), two,
// or more: a thin plate welded onto a wall along a line (a lifter in a
// drum) makes an edge of three faces, which CAD exports produce and the
// contact below handles like any other, so it is allowed (as LIGGGHTS
// allows it). Refused (MeshError, check_mesh): no triangles, a vertex id out
// of range, a vertex used twice by one triangle, a non-finite coordinate, a
// degenerate triangle (is_degenerate_triangle), and a triangle repeated with
// the same three vertices in any order (it would double every force on it).
//
// The closest point of one triangle (Voronoi regions; Ericson, Real-Time
// Collision Detection, 5.1.5, in this notation). Corners x_0, x_1, x_2;
// side k joins x_k to x_k+1 (indices mod 3). For a point c:
//   s_k = (c - a_k) . m_k   the in-plane distance of c beyond side k, m;
//         m_k = unit (x_k+1 - x_k) x N lies in the face's plane,
//         perpendicular to side k, and points out of the triangle (the
//         triangle lies where s_k <= 0); a_k is one end of the side.
//   tau_e = (c - x_0e) . (x_1e - x_0e)   for an edge from x_0e to x_1e, m^2:
//         the projection of c on the edge's line, 0 at x_0e and |x_1e - x_0e|^2
//         at x_1e.
// Every point of space lies in exactly one region, by where its closest
// point on the triangle is:
//   face      s_0, s_1, s_2 < 0: c projects into the triangle, and the
//             projection q = c - d N, d = (c - x_0) . N, is closest (any
//             other point of the plane is farther by Pythagoras);
//   edge      s_k >= 0 and 0 < tau < |edge|^2: the triangle lies on the far
//             side of the side's line, so the closest point of the plane
//             half that holds it is on that line, at parameter
//             t = tau / |edge|^2, which is inside the side:
//             q = x_0e + t (x_1e - x_0e);
//   vertex    (c - x_j) . (x_i - x_j) <= 0 for both other corners x_i, i.e.
//             c lies beyond x_j on both sides at x_j (tau <= 0 or
//             tau >= |edge|^2 on each, whichever end x_j is): q = x_j.
// (A point beyond x_j on both sides does not project into the triangle: if
// it projected to x_j + alpha u + beta w, u and w the sides from x_j and
// alpha, beta >= 0, then alpha times the first condition plus beta times
// the second gives |alpha u + beta w|^2 <= 0, so alpha = beta = 0.)
//
// The contacts of a sphere with the mesh. A feature (face, edge or vertex)
// gives a contact when its closest point q is the closest point of every
// face around it, i.e. the centre c lies in that feature's region for each
// of those faces: then q is a local minimum of the distance from c to the
// mesh's surface and the sphere, which overlaps the surface there, is
// pressed against it at q. With the distance |c - q| < R (R the radius):
//   n = (c - q) / |c - q|   unit, from the mesh to the sphere's centre
//                           (for a face: sign(d) N);
//   h = R - |c - q| > 0     the overlap, m.
// This is the deduplication rule. Its reason: where the surface is flat or
// convex and smooth the sphere is pressed against one point of it and must
// feel one contact, as from the analytic plane; where it is concave (a
// sphere in a V) it touches both sides and feels two, which is the physics.
// As a rule on the contacts that the faces find one by one:
//   1. a face contact (s_0, s_1, s_2 < 0) is always kept;
//   2. an edge contact (0 < tau < |edge|^2) is kept only if c lies beyond
//      the edge's side in every face of the edge (s >= 0 in each). So it is
//      dropped when a face of the edge has a face contact (that face found
//      s < 0, the same number), and also when c lies inside a face of the
//      edge across it although that face has no contact there: on a plane
//      of many triangles an edge that crosses the sphere's contact patch
//      comes within R of the centre, seen from the face beyond it, but the
//      plane's closest point is elsewhere;
//   3. a vertex contact is kept only if c is beyond the vertex on every edge
//      at it, and no face or edge at the vertex has a contact;
//   4. the same edge or vertex reached from several faces counts once (by
//      id), and a contact whose point coincides with one already kept
//      (within 1e-9 (R + max_i |c_i|), rounding) is dropped: a centre right
//      above the shared edge or vertex of coplanar triangles that rounding
//      lets two of them claim, or the seam of a mesh whose copies of a
//      vertex were not welded;
//   5. a sphere that overlaps the mesh has at least one contact: where
//      rounding fails every test (a centre within about an ulp of the line
//      over a vertex, where the sides' distances and the projections tau
//      are noise and can disagree), the nearest point of the candidate
//      faces gives it, as the feature it lies on.
// Flat edges and vertices. An edge whose two faces lie in one plane (their
// normals within 1e-12 rad, the faces on either side of it) and a vertex
// whose faces all do (inside a flat part) pass their test only where c is
// over them, and there their contact is the plane's; it is computed as the
// plane's: n = sign(d) N, h = R - |d|, q = c - d N from one of their faces.
// (A centre that rounding lets pass an ulp beside the edge then still gets
// the plane's normal, not one tilted by an ulp over the height.)
// On a plane of triangles every position of the centre gives exactly one
// contact, the plane's to round-off, on edges and on vertices of any
// valence: the sides' distances s are measured from the edge's
// lower-numbered vertex, so the two faces of an edge compute the same s
// with opposite signs when their normals are equal (exactly so for a plane
// along the axes), and a centre on the edge is claimed by both or neither.
// Over the convex edge of a box the sphere gets one edge contact with n
// from the edge; at the box's corner one vertex contact; in a V two face
// contacts, one per side.
//
// Limit: a concave crease that is nearly flat (a cylinder tessellated and
// seen from inside, crease angle theta between the faces) gives two face
// contacts, each of overlap about h, while the centre lies over both faces,
// within about (R - h) tan(theta / 2) of the crease on either side: the
// normal force about doubles there (72 facets round a drum, theta = 5 deg:
// a band of 0.087 R). Curved equipment seen from inside is better an
// analytic wall, or a finer mesh.
//
// History. mesh_contacts is stateless and names each contact by its feature
// and id. A tangential spring or twist carried between steps must follow
// the contact when it moves from a face to its neighbour (rolling over a
// flat mesh moves it from face to face, and over an edge or vertex exactly
// between them): match each new contact of a sphere with that sphere's
// old contacts on the same mesh first by feature and id, else by the
// nearest old contact point within the contact's reach (the old contact
// radius sqrt(R h) plus the distance the sphere moved) whose normal agrees
// (n_old . n_new > 0, say), and carry its history over, rotated into the new
// tangent plane (remove the component along n_new, keep the length), as
// for a contact whose normal turns. Several new contacts may not take one
// old record; an unmatched new contact starts from zero. Face, edge and
// vertex ids are stable while the mesh moves (set_vertices).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tumble/core/error.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble {

struct TriangleMesh {
    std::vector<Vec3> vertices;                           // m
    std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex ids; N by the right-hand rule of their order
};

// Joins the corners of separate triangles (three each, in order) into shared
// vertices: corners with identical coordinates (the same three doubles; -0
// equals +0) become one vertex, numbered in order of first appearance. The
// triangles keep their order and corner order. Exact equality, not a
// tolerance: CAD exports write a shared vertex with the same numbers each
// time, and a tolerance would join corners a user placed apart on purpose
// (a seam left open is harmless: rule 4 above).
TriangleMesh weld_triangles(std::span<const std::array<Vec3, 3>> corners);

// True when the triangle's area, |(b - a) x (c - a)| / 2, is not above
// 1e-12 times its longest edge squared (zero-area triangles included, and
// any with a non-finite coordinate): its normal would be noise.
bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c);

// A triangle that cannot be part of a mesh. what() is "triangle K: REASON"
// with K counting from 1 (the triangle's place in a file); triangle() is the
// index, from 0.
class MeshError : public Error {
public:
    MeshError(std::size_t triangle, std::string reason);
    std::size_t triangle() const { return triangle_; }
    const std::string& reason() const { return reason_; }

private:
    std::size_t triangle_;
    std::string reason_;
};

// Throws MeshError for the first triangle that cannot be part of a mesh
// (the list at the top), tumble::Error for a mesh without triangles.
void check_mesh(const TriangleMesh& mesh);

// What a face needs for the contact test, kept per face for speed.
struct FaceGeometry {
    std::array<Vec3, 3> corner;               // the vertices in the triangle's order, m
    Vec3 normal;                              // N, unit, right-hand rule of the corner order
    std::array<Vec3, 3> side_normal;          // m_k, unit, in-plane, out of the triangle across side k
    std::array<std::uint8_t, 3> side_origin;  // the corner at side k's lower vertex id: a_k = corner[side_origin[k]]

    // s_k, m: > 0 beyond side k, < 0 on the triangle's side of its line.
    double side_distance(int k, const Vec3& c) const { return dot(c - corner[side_origin[k]], side_normal[k]); }
};

inline constexpr std::uint32_t no_face = 0xffffffff;

// An edge from its lower vertex id x_0e to the other, x_1e.
struct EdgeGeometry {
    Vec3 origin;                    // x_0e, m
    Vec3 direction;                 // x_1e - x_0e, m
    double length2 = 0.0;           // |x_1e - x_0e|^2, m^2
    std::uint32_t plane = no_face;  // for a flat edge (the header) the face whose plane gives its contact
};

// The mesh with its topology (which never changes) and the geometry of its
// faces and edges (recomputed when the mesh moves). Ids: faces are the
// triangles' indices; edges are numbered in order of (lower vertex id,
// higher vertex id); vertices keep their ids. Lists of ids are in
// increasing order.
class MeshTopology {
public:
    explicit MeshTopology(TriangleMesh mesh);  // check_mesh first

    // Moves the vertices (a moving wall: each step, or whenever the mesh is
    // placed anew) keeping every id; the same count as before. MeshError
    // when a triangle becomes degenerate or a coordinate is not finite, and
    // the mesh is then unchanged.
    void set_vertices(std::span<const Vec3> vertices);

    std::size_t face_count() const { return triangles_.size(); }
    std::size_t edge_count() const { return edges_.size(); }
    std::size_t vertex_count() const { return vertices_.size(); }

    std::span<const Vec3> vertices() const { return vertices_; }
    std::span<const std::array<std::uint32_t, 3>> triangles() const { return triangles_; }
    // Each edge's two vertex ids, lower first.
    std::span<const std::array<std::uint32_t, 2>> edges() const { return edges_; }
    // Each face's edge ids: edge k joins the triangle's vertices k and k + 1 (mod 3).
    std::span<const std::array<std::uint32_t, 3>> face_edges() const { return face_edges_; }
    // The sides along an edge, as 3 f + k (face f, its side k): one for an
    // open edge, two inside a surface, more where plates meet.
    std::span<const std::uint32_t> edge_sides(std::uint32_t e) const {
        return {edge_sides_.data() + edge_side_start_[e], edge_sides_.data() + edge_side_start_[e + 1]};
    }
    std::span<const std::uint32_t> vertex_faces(std::uint32_t v) const {
        return {vertex_faces_.data() + vertex_face_start_[v], vertex_faces_.data() + vertex_face_start_[v + 1]};
    }
    std::span<const std::uint32_t> vertex_edges(std::uint32_t v) const {
        return {vertex_edges_.data() + vertex_edge_start_[v], vertex_edges_.data() + vertex_edge_start_[v + 1]};
    }

    const FaceGeometry& face(std::uint32_t f) const { return faces_[f]; }
    const EdgeGeometry& edge(std::uint32_t e) const { return edge_geometry_[e]; }
    // For a flat vertex (the header) the face whose plane gives its contact, else no_face.
    std::uint32_t vertex_plane(std::uint32_t v) const { return vertex_plane_[v]; }

private:
    void update_geometry();

    std::vector<Vec3> vertices_;
    std::vector<std::array<std::uint32_t, 3>> triangles_;
    std::vector<std::array<std::uint32_t, 2>> edges_;
    std::vector<std::array<std::uint32_t, 3>> face_edges_;
    std::vector<std::uint32_t> edge_side_start_, edge_sides_;      // per edge, from start[e] to start[e + 1]
    std::vector<std::uint32_t> vertex_face_start_, vertex_faces_;  // per vertex, likewise
    std::vector<std::uint32_t> vertex_edge_start_, vertex_edges_;
    std::vector<FaceGeometry> faces_;
    std::vector<EdgeGeometry> edge_geometry_;
    std::vector<std::uint32_t> vertex_plane_;
};

// Why the mesh does not bound a region of space, or empty when it does:
// every edge has exactly two faces, which run along it in opposite
// directions (a closed surface, its normals all outward or all inward).
// A fill inside or outside a mesh needs this (a chute has no inside).
std::string closed_surface_problem(const MeshTopology& mesh);

// The winding number of a closed surface about the point x: the sum of the
// solid angles its faces subtend at x over 4 pi. 1 inside a surface whose
// normals point out, -1 inside one whose normals point in, 0 outside; in
// between only within rounding of the surface. The solid angle of a
// triangle with corners a, b, c seen from x (Van Oosterom & Strackee, IEEE
// Trans. Biomed. Eng. 30, 125, 1983), with A = a - x, B = b - x, C = c - x:
//   tan(Omega / 2) = A . (B x C) / (|A||B||C| + (A . B)|C| + (B . C)|A| + (C . A)|B|),
// Omega > 0 where x lies behind the face (against N). Cost: every face, per
// point.
double winding_number(const MeshTopology& mesh, const Vec3& x);

enum class MeshFeature : std::uint8_t { face, edge, vertex };

// One contact of a sphere with a mesh (the rule above).
struct MeshContact {
    MeshFeature feature = MeshFeature::face;
    std::uint32_t id = 0;  // the face's, edge's or vertex's id
    Vec3 point;            // q, the closest point on the mesh, m
    Vec3 n;                // unit, from q to the sphere's centre
    double overlap = 0.0;  // h = R - |centre - q| > 0, m
};

// The contacts of the sphere (centre, radius R) with the mesh, after the
// rule above, into `out` (cleared first; no allocation once its capacity
// suffices): face contacts first, then edges, then vertices, each in the
// order of `candidate_faces`. candidate_faces must hold, once each, every
// face within R of the centre (FacetGrid::candidates, or all faces); the
// test of an edge or vertex looks at all its faces or edges, listed or not.
// A centre exactly on an edge or vertex (distance 0: no direction) gives no
// contact with it.
void mesh_contacts(const MeshTopology& mesh, const Vec3& centre, double radius,
                   std::span<const std::uint32_t> candidate_faces, std::vector<MeshContact>& out);

// The faces of candidate_faces that may lie within `reach` of the centre,
// appended to out in their order: those whose bound sqrt(d^2 + s^2), with
// s = max(s_max, 0) the in-plane distance beyond the farthest side (never
// more than the true distance: the header), is below reach. A sphere of
// radius R whose centre stays within reach - R of `centre` can touch no
// other face of the candidates (Simulation's list of the faces near each
// sphere).
void faces_within(const MeshTopology& mesh, const Vec3& centre, double reach,
                  std::span<const std::uint32_t> candidate_faces, std::vector<std::uint32_t>& out);

}  // namespace tumble
