// The narrow phase: contacts between two convex shapes (collide.h).
//
// Two hulls: the separating axis test, then a manifold.
//   The axes tried are the face normals of A, the face normals of B, and the cross products of
//   an edge of A and an edge of B, but only for the edge pairs that make a face of the Minkowski
//   difference A - B: those whose arcs cross on the Gauss map (an edge's arc joins the normals
//   of its two faces; B's are negated). Other edge pairs can never give the largest separation
//   when the hulls overlap, and skipping them makes a 64-vertex mesh's edge test affordable.
//   Along each axis the separation is the gap between the two hulls' projections; the largest
//   over all axes is their separation (exact when they overlap: minus the penetration depth;
//   a lower bound on the distance when they do not). Above the margin: no contact.
//
//   Face contact (the largest separation is a face's): the reference face is that face, the
//   incident face is the other hull's face most nearly opposite to it; the incident face is
//   clipped (Sutherland-Hodgman) by the planes through the reference face's edges, at right
//   angles to it, and each clipped point that lies less than the margin above the reference
//   plane is a contact, its depth measured to that plane, its point midway between. More than
//   four points are cut to four (reduce_manifold).
//   Edge contact (the largest is an edge pair's): one point, midway between the closest points
//   of the two edges.
//
//   The choice is biased toward faces: an edge pair wins only when its separation exceeds the
//   best face's by kFaceBiasRelative of that face's separation plus kFaceBiasAbsolute, and B's
//   face wins over A's only by the same margin. A box resting on another gives the same
//   separation along its face normal as along edge pairs almost parallel to it, and as its
//   neighbour's face; without the bias the winner would flicker with rounding from step to
//   step, and with it the manifold and its feature ids.
//
// A sphere: the nearest point of the hull to its centre (shape_queries.cpp), or the other
// sphere's centre.
//
// Feature ids (ContactPoint::feature), 32 bits: the kind (3 bits), whether the reference face
// is b's (1 bit), then four 7-bit fields:
//   FaceVertex    reference face, incident vertex
//   FaceEdgeSide  reference face, the incident edge's two vertices, the reference face's side
//                 that cut it
//   FaceCorner    reference face, the two sides of the reference face whose corner it is
//   FaceSupport   reference face, the incident vertex (a face contact whose clipped face kept
//                 no point: the incident hull's deepest vertex)
//   EdgeEdge      (no flag) the edge of a, the edge of b, 14 bits each
//   SphereFace, SphereEdge, SphereVertex: the hull's face, edge (its two vertices) or vertex.
// Vertex indices are the hull's, the same whichever incident face a point came from, so a box
// on its edge keeps its ids when the incident face swaps between the edge's two faces. Seven
// bits hold every index of a collision hull (64 vertices, at most 124 faces, a face of at most
// 64 sides); a larger hull's ids wrap and may repeat, which only costs a warm start.
#include "physics/collide.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "collide_internal.h"
#include "manifold.h"
#include "physics/portable_math.h"

namespace softbody {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The bias toward face contacts (see above). Relative: 5% of the face's separation, so deep
// overlaps are judged in proportion. Absolute: half a millimetre, a few times the solver's slop
// (2e-4 m, contact_solver.h), which is the depth a resting pair hovers at.
constexpr double kFaceBiasRelative = 0.05;
constexpr double kFaceBiasAbsolute = 5e-4;  // m
// Cutting a manifold to four points (reduce_manifold), points within kManifoldDepthTie of the
// deepest count as deepest, and the earliest in clipping order is taken: half the solver's
// slop. A cylinder standing on its cap keeps the same four of its 32 rim points while it rocks
// by less than that, instead of starting from whichever corner is a hair deeper in each step.
constexpr double kManifoldDepthTie = 1e-4;  // m
// Clipped points closer than this are one point: clipping through a corner of the reference
// face, or past an incident vertex that lies on a side plane, yields the same point two or three
// times over, differing only by rounding. A micrometre is far below any body's size here.
constexpr double kSamePoint = 1e-6;  // m
// Edge pairs closer to parallel than this sine give no axis of their own: their cross product
// is all rounding, and the face normals beside them already cover the direction.
constexpr double kParallelSine = 1e-6;

enum class Kind : std::uint32_t {
    FaceVertex = 0,
    FaceEdgeSide = 1,
    FaceCorner = 2,
    FaceSupport = 3,
    EdgeEdge = 4,
    SphereFace = 5,
    SphereEdge = 6,
    SphereVertex = 7,
};

constexpr std::uint32_t pack(Kind kind, bool flag, std::uint32_t f, std::uint32_t a, std::uint32_t b = 0,
                             std::uint32_t c = 0) {
    return std::uint32_t(kind) << 29 | std::uint32_t(flag) << 28 | (f & 127u) << 21 | (a & 127u) << 14 |
           (b & 127u) << 7 | (c & 127u);
}

constexpr std::uint32_t pack_edges(std::uint32_t edge_a, std::uint32_t edge_b) {
    return std::uint32_t(Kind::EdgeEdge) << 29 | (edge_a & 0x3FFFu) << 14 | (edge_b & 0x3FFFu);
}

double biased(double separation) { return separation + kFaceBiasRelative * std::abs(separation) + kFaceBiasAbsolute; }

// --- Spheres -------------------------------------------------------------------------------------

void sphere_sphere(double ra, const Vec3d& ca, double rb, const Vec3d& cb, double margin, std::vector<ContactPoint>& out) {
    const Vec3d d = ca - cb;
    const double distance = length(d);
    const double separation = distance - ra - rb;
    if (separation > margin) return;
    // Concentric: any direction will do; up is as good as another.
    const Vec3d n = distance > 0.0 ? d / distance : Vec3d{0.0, 0.0, 1.0};
    out.push_back({((ca - n * ra) + (cb + n * rb)) * 0.5, n, -separation, 0});
}

// A sphere against a hull; `sphere_is_a` says which way the normal goes (out of b toward a).
void sphere_hull(double r, const Vec3d& c, const ConvexHull& hull, const Transform& T, bool sphere_is_a, double margin,
                 std::vector<ContactPoint>& out) {
    const Vec3d local = T.R.transposed() * (c - T.x);
    const double reach = margin + r;
    const NearestOnHull q = nearest_on_hull(hull, local, reach);
    if (q.distance > reach) return;  // out of reach (perhaps only a bound)
    const double separation = q.distance - r;
    if (separation > margin) return;
    const Vec3d n = T.R * q.normal;  // out of the hull
    ContactPoint contact;
    contact.point = T.apply((q.point + (local - q.normal * r)) * 0.5);
    contact.normal = sphere_is_a ? n : -n;
    contact.depth = -separation;
    switch (q.feature) {
        case NearestOnHull::Feature::Face: contact.feature = pack(Kind::SphereFace, sphere_is_a, q.index[0], 0); break;
        case NearestOnHull::Feature::Edge:
            contact.feature = pack(Kind::SphereEdge, sphere_is_a, 0, q.index[0], q.index[1]);
            break;
        case NearestOnHull::Feature::Vertex: contact.feature = pack(Kind::SphereVertex, sphere_is_a, 0, q.index[0]); break;
    }
    out.push_back(contact);
}

// --- Two hulls: the separating axes -------------------------------------------------------------

struct FaceQuery {
    double separation = -kInf;
    std::uint32_t face = 0;
};

// The faces of A as axes, with B in A's axes by T. Along face f (normal n, offset d), the gap is
// min over B's vertices v of n . (R v + x) - d. Stops early once a gap exceeds `stop_above`.
FaceQuery query_faces(const ConvexHull& A, const ConvexHull& B, const Transform& T, double stop_above) {
    const Mat3 Rt = T.R.transposed();
    FaceQuery best;
    for (std::size_t f = 0; f < A.faces.size(); ++f) {
        const ConvexHull::Face& face = A.faces[f];
        const Vec3d n_in_b = Rt * face.normal;
        double lowest = kInf;
        for (const Vec3d& v : B.vertices) lowest = std::min(lowest, dot(n_in_b, v));
        const double separation = dot(face.normal, T.x) + lowest - face.offset;
        if (separation > best.separation) {
            best = {separation, std::uint32_t(f)};
            if (separation > stop_above) break;
        }
    }
    return best;
}

struct EdgeQuery {
    double separation = -kInf;
    std::uint32_t edge_a = 0, edge_b = 0;
    Vec3d axis;  // in A's axes, out of A toward B
    bool found = false;
};

// The edge pairs of A and B (B in A's axes by T) that make faces of the Minkowski difference.
// Edge of A: ends p, q, faces' normals a, b. Edge of B: faces' normals negated, c and d (the
// faces of -B). Their arcs a-b and c-d cross when c and d lie on opposite sides of the plane
// of a and b, a and b on opposite sides of the plane of c and d, and the two crossings of the
// great circles that lie on the arcs are the same one, not antipodes (the last product).
//
// The first test rejects most pairs and depends only on B's faces: the side of the plane of a
// and b that each face's normal lies on is found once for each edge of A (one dot product a
// face of B, over arrays of the normals' coordinates), and each edge of B reads its two faces'
// (a prism of 32 sides has 34 faces and 96 edges). What the other tests need of B's edges,
// d x c and the ends placed in A's axes, is found once a query. The same numbers as testing
// every pair in full: dot(-n, v) is exactly -dot(n, v), so c.(b x a) d.(b x a) is the product
// of the two sides read.
EdgeQuery query_edges(const CollisionShape& A, const CollisionShape& B, const Transform& T, double stop_above) {
    const ConvexHull& ha = *A.hull;
    const ConvexHull& hb = *B.hull;
    struct Scratch {
        std::vector<double> nx, ny, nz, side;  // B's face normals in A's axes; their sides of a plane
        std::vector<Vec3d> dxc;                // each edge of B's d x c
        std::vector<Vec3d> vertices;           // B's vertices in A's axes
    };
    thread_local Scratch w;
    const std::size_t faces = hb.faces.size();
    w.nx.resize(faces);
    w.ny.resize(faces);
    w.nz.resize(faces);
    w.side.resize(faces);
    for (std::size_t f = 0; f < faces; ++f) {
        const Vec3d n = T.R * hb.faces[f].normal;
        w.nx[f] = n.x;
        w.ny[f] = n.y;
        w.nz[f] = n.z;
    }
    const auto normal_b = [&](std::uint32_t f) { return Vec3d{w.nx[f], w.ny[f], w.nz[f]}; };
    w.dxc.resize(B.edges.size());
    for (std::size_t j = 0; j < B.edges.size(); ++j) {
        const HullEdge& g = B.edges[j];
        w.dxc[j] = cross(-normal_b(g.faces[1]), -normal_b(g.faces[0]));
    }
    w.vertices.resize(hb.vertices.size());
    for (std::size_t k = 0; k < hb.vertices.size(); ++k) w.vertices[k] = T.apply(hb.vertices[k]);
    const double *nx = w.nx.data(), *ny = w.ny.data(), *nz = w.nz.data();
    double* side = w.side.data();

    EdgeQuery best;
    for (std::size_t i = 0; i < A.edges.size(); ++i) {
        const HullEdge& e = A.edges[i];
        const Vec3d p = ha.vertices[e.vertices[0]];
        const Vec3d edge_a = ha.vertices[e.vertices[1]] - p;
        const Vec3d a = ha.faces[e.faces[0]].normal, b = ha.faces[e.faces[1]].normal;
        const Vec3d bxa = cross(b, a);
        const double length_a = length(edge_a);
        for (std::size_t f = 0; f < faces; ++f) side[f] = nx[f] * bxa.x + ny[f] * bxa.y + nz[f] * bxa.z;
        for (std::size_t j = 0; j < B.edges.size(); ++j) {
            const HullEdge& g = B.edges[j];
            const double s0 = side[g.faces[0]], s1 = side[g.faces[1]];
            if (!(s0 * s1 < 0.0)) continue;  // most pairs end here
            const double cba = -s0;
            const double adc = dot(a, w.dxc[j]), bdc = dot(b, w.dxc[j]);
            if (!(adc * bdc < 0.0 && cba * bdc > 0.0)) continue;
            const Vec3d& p_b = w.vertices[g.vertices[0]];
            const Vec3d edge_b = w.vertices[g.vertices[1]] - p_b;
            Vec3d axis = cross(edge_a, edge_b);
            const double l = length(axis);
            if (!(l > kParallelSine * length_a * length(edge_b))) continue;
            axis = axis / l;
            // The axis lies on A's arc, between a and b: out of A.
            if (dot(axis, a + b) < 0.0) axis = -axis;
            const double separation = dot(axis, p_b - p);
            if (separation > best.separation) {
                best = {separation, std::uint32_t(i), std::uint32_t(j), axis, true};
                if (separation > stop_above) return best;
            }
        }
    }
    return best;
}

// --- Two hulls: the manifold ---------------------------------------------------------------------

// The closest points of the segments p1-q1 and p2-q2 (both of non-zero length): minimise
// |p1 + s d1 - p2 - t d2| over s, t in [0, 1], clamping s then t.
void closest_points(const Vec3d& p1, const Vec3d& q1, const Vec3d& p2, const Vec3d& q2, Vec3d& c1, Vec3d& c2) {
    const Vec3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const double a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r);
    const double denom = a * e - b * b;
    double s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    double t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
    c1 = p1 + d1 * s;
    c2 = p2 + d2 * t;
}

// A vertex of the incident polygon as it is clipped, and the piece of boundary that leaves it
// toward the next vertex: an incident edge (u, v), or a side k of the reference face.
struct ClipVertex {
    Vec3d p;
    std::uint32_t feature = 0;
    bool along_side = false;
    std::uint32_t u = 0, v = 0, k = 0;
};

// A face contact: `ref`'s face `ref_face` against the incident hull `inc` (in ref's axes by
// T). `ref_is_b` says which way the normal goes and marks the feature ids.
void face_contact(const ConvexHull& ref, const Transform& ref_world, std::uint32_t ref_face, const ConvexHull& inc,
                  const Transform& T, bool ref_is_b, double margin, std::vector<ContactPoint>& out) {
    const ConvexHull::Face& face = ref.faces[ref_face];
    const Vec3d n = face.normal;
    // The incident face: the one most nearly opposite n.
    const Vec3d n_in_inc = T.R.transposed() * n;
    std::size_t incident = 0;
    double most_opposite = kInf;
    for (std::size_t f = 0; f < inc.faces.size(); ++f) {
        const double along = dot(inc.faces[f].normal, n_in_inc);
        if (along < most_opposite) {
            most_opposite = along;
            incident = f;
        }
    }
    const std::vector<std::uint32_t>& loop = inc.faces[incident].vertices;
    std::vector<ClipVertex> polygon, clipped;
    polygon.reserve(loop.size() + face.vertices.size());
    clipped.reserve(loop.size() + face.vertices.size());
    for (std::size_t j = 0; j < loop.size(); ++j) {
        const std::uint32_t u = loop[j], v = loop[(j + 1) % loop.size()];
        polygon.push_back({T.apply(inc.vertices[u]), pack(Kind::FaceVertex, ref_is_b, ref_face, u), false, u, v, 0});
    }
    // Sutherland-Hodgman against each side plane: through the side, at right angles to the
    // face, normal m = side x n pointing out of the face (its loop turns counter-clockwise
    // about n). A vertex is kept when m . p <= m . (side's start).
    const std::vector<std::uint32_t>& sides = face.vertices;
    for (std::size_t k = 0; k < sides.size() && !polygon.empty(); ++k) {
        const Vec3d r0 = ref.vertices[sides[k]], r1 = ref.vertices[sides[(k + 1) % sides.size()]];
        const Vec3d m = cross(r1 - r0, n);
        const double offset = dot(m, r0);
        clipped.clear();
        for (std::size_t j = 0; j < polygon.size(); ++j) {
            const ClipVertex& cur = polygon[j];
            const ClipVertex& next = polygon[(j + 1) % polygon.size()];
            const double dc = dot(m, cur.p) - offset, dn = dot(m, next.p) - offset;
            if (dc <= 0.0) clipped.push_back(cur);
            if ((dc < 0.0 && dn > 0.0) || (dc > 0.0 && dn < 0.0)) {
                ClipVertex cut = cur;  // on cur's piece of boundary
                cut.p = cur.p + (next.p - cur.p) * (dc / (dc - dn));
                cut.feature = cur.along_side ? pack(Kind::FaceCorner, ref_is_b, ref_face, cur.k, std::uint32_t(k))
                                             : pack(Kind::FaceEdgeSide, ref_is_b, ref_face, cur.u, cur.v, std::uint32_t(k));
                if (dc < 0.0) {  // leaving: the boundary goes on along side k
                    cut.along_side = true;
                    cut.k = std::uint32_t(k);
                }
                clipped.push_back(cut);
            }
        }
        std::swap(polygon, clipped);
    }
    clipped.clear();
    for (const ClipVertex& c : polygon) {
        if (clipped.empty() || length(c.p - clipped.back().p) > kSamePoint) clipped.push_back(c);
    }
    if (clipped.size() > 1 && length(clipped.back().p - clipped.front().p) <= kSamePoint) clipped.pop_back();
    const Vec3d normal = ref_world.R * (ref_is_b ? n : -n);
    std::vector<ContactPoint> manifold;
    for (const ClipVertex& c : clipped) {
        const double separation = dot(n, c.p) - face.offset;
        if (separation > margin) continue;
        manifold.push_back({ref_world.apply(c.p - n * (0.5 * separation)), normal, -separation, c.feature});
    }
    if (manifold.empty()) {
        // Nothing of the incident face lies over the reference face (two hulls apart whose
        // nearest features are corners beyond each other's faces): one point from the
        // incident hull's deepest vertex, its gap along n, which is still a bound on how far
        // they may close along n.
        std::uint32_t deepest = 0;
        double lowest = kInf;
        for (std::size_t i = 0; i < inc.vertices.size(); ++i) {
            const double along = dot(n, T.apply(inc.vertices[i]));
            if (along < lowest) {
                lowest = along;
                deepest = std::uint32_t(i);
            }
        }
        const double separation = lowest - face.offset;
        if (separation > margin) return;
        const Vec3d p = T.apply(inc.vertices[deepest]);
        manifold.push_back({ref_world.apply(p - n * (0.5 * separation)), normal, -separation,
                            pack(Kind::FaceSupport, ref_is_b, ref_face, deepest)});
    }
    reduce_manifold(manifold, normal, kManifoldDepthTie);
    out.insert(out.end(), manifold.begin(), manifold.end());
}

void edge_contact(const CollisionShape& A, const Transform& TA, const CollisionShape& B, const Transform& b_in_a,
                  const EdgeQuery& q, std::vector<ContactPoint>& out) {
    const HullEdge& ea = A.edges[q.edge_a];
    const HullEdge& eb = B.edges[q.edge_b];
    Vec3d ca, cb;
    closest_points(A.hull->vertices[ea.vertices[0]], A.hull->vertices[ea.vertices[1]],
                   b_in_a.apply(B.hull->vertices[eb.vertices[0]]), b_in_a.apply(B.hull->vertices[eb.vertices[1]]), ca, cb);
    out.push_back({TA.apply((ca + cb) * 0.5), TA.R * -q.axis, -q.separation, pack_edges(q.edge_a, q.edge_b)});
}

void hull_hull(const CollisionShape& A, const Transform& TA, const CollisionShape& B, const Transform& TB,
               double margin, std::vector<ContactPoint>& out) {
    const Transform b_in_a = relative_transform(TA, TB), a_in_b = relative_transform(TB, TA);
    const FaceQuery fa = query_faces(*A.hull, *B.hull, b_in_a, margin);
    if (fa.separation > margin) return;
    const FaceQuery fb = query_faces(*B.hull, *A.hull, a_in_b, margin);
    if (fb.separation > margin) return;
    const EdgeQuery ee = query_edges(A, B, b_in_a, margin);
    if (ee.separation > margin) return;
    if (ee.found && ee.separation > biased(std::max(fa.separation, fb.separation))) {
        edge_contact(A, TA, B, b_in_a, ee, out);
    } else if (fb.separation > biased(fa.separation)) {
        face_contact(*B.hull, TB, fb.face, *A.hull, a_in_b, true, margin, out);
    } else {
        face_contact(*A.hull, TA, fa.face, *B.hull, b_in_a, false, margin, out);
    }
}

}  // namespace

// --- Shapes ----------------------------------------------------------------------------------------

namespace {
// FNV-1a over the bits of the numbers that make a shape.
std::uint64_t stamp_of(std::uint64_t stamp, double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    for (int k = 0; k < 8; ++k) stamp = (stamp ^ ((bits >> (8 * k)) & 0xff)) * 0x100000001b3ull;
    return stamp;
}
constexpr std::uint64_t kStampStart = 0xcbf29ce484222325ull;
}  // namespace

CollisionShape sphere_shape(double radius) {
    CollisionShape shape;
    shape.radius = radius;
    shape.bounding_radius = radius;
    shape.stamp = stamp_of(kStampStart, radius);
    return shape;
}

CollisionShape hull_shape(std::shared_ptr<const ConvexHull> hull) {
    if (!hull) throw std::invalid_argument("collision shape: no hull");
    CollisionShape shape;
    const ConvexHull& h = *hull;
    // Each edge's two faces: the face whose loop runs first -> second, and the one running back.
    // The edges sorted by their vertices, to find a face's sides among them.
    std::vector<std::pair<std::array<std::uint32_t, 2>, std::uint32_t>> sorted;
    sorted.reserve(h.edges.size());
    for (std::size_t e = 0; e < h.edges.size(); ++e) sorted.push_back({h.edges[e], std::uint32_t(e)});
    std::sort(sorted.begin(), sorted.end());
    constexpr std::uint32_t kNone = ~0u;
    shape.edges.resize(h.edges.size());
    for (std::size_t e = 0; e < h.edges.size(); ++e) shape.edges[e] = {h.edges[e], {kNone, kNone}};
    const auto broken = [](const std::string& what) {
        throw std::invalid_argument("collision shape: the hull is not a closed polyhedron (" + what + ")");
    };
    for (std::size_t f = 0; f < h.faces.size(); ++f) {
        const std::vector<std::uint32_t>& loop = h.faces[f].vertices;
        for (std::size_t j = 0; j < loop.size(); ++j) {
            const std::uint32_t u = loop[j], v = loop[(j + 1) % loop.size()];
            const std::array<std::uint32_t, 2> key{std::min(u, v), std::max(u, v)};
            const auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(key, 0u));
            if (it == sorted.end() || it->first != key) broken("face " + std::to_string(f) + " has a side not in its edges");
            std::uint32_t& slot = shape.edges[it->second].faces[u < v ? 0 : 1];
            if (slot != kNone) broken("an edge is shared by more than two faces, or twice in one direction");
            slot = std::uint32_t(f);
        }
    }
    for (const HullEdge& e : shape.edges) {
        if (e.faces[0] == kNone || e.faces[1] == kNone) broken("an edge with one face");
    }
    for (const Vec3d& v : h.vertices) shape.bounding_radius = std::max(shape.bounding_radius, length(v));
    double least_angle = 2.0 * kMostContactTurn;
    for (const HullEdge& e : shape.edges) {
        const double cosine = std::clamp(dot(h.faces[e.faces[0]].normal, h.faces[e.faces[1]].normal), -1.0, 1.0);
        least_angle = std::min(least_angle, portable::acos(cosine));
    }
    shape.contact_turn = std::clamp(0.5 * least_angle, kLeastContactTurn, kMostContactTurn);
    // The vertices and the faces' planes make the hull (the same vertices in another order are
    // another stamp: only a false "different", never a false "same").
    shape.stamp = stamp_of(kStampStart, double(h.vertices.size()));
    for (const Vec3d& v : h.vertices) shape.stamp = stamp_of(stamp_of(stamp_of(shape.stamp, v.x), v.y), v.z);
    for (const ConvexHull::Face& f : h.faces) shape.stamp = stamp_of(stamp_of(stamp_of(stamp_of(shape.stamp, f.normal.x), f.normal.y), f.normal.z), f.offset);
    shape.hull = std::move(hull);
    return shape;
}

CollisionShape collision_shape(const RigidBody& body) {
    if (body.shape == ShapeKind::Sphere) return sphere_shape(body.radius);
    return hull_shape(body.hull);
}

// --- The narrow phase ------------------------------------------------------------------------------

void collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb, double margin,
             std::vector<ContactPoint>& out) {
    if (a.is_sphere() && b.is_sphere()) {
        sphere_sphere(a.radius, pa.x, b.radius, pb.x, margin, out);
    } else if (a.is_sphere()) {
        sphere_hull(a.radius, pa.x, *b.hull, world_transform(pb), true, margin, out);
    } else if (b.is_sphere()) {
        sphere_hull(b.radius, pb.x, *a.hull, world_transform(pa), false, margin, out);
    } else {
        hull_hull(a, world_transform(pa), b, world_transform(pb), margin, out);
    }
}

double separation_bound(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb) {
    if (a.is_sphere() && b.is_sphere()) return length(pa.x - pb.x) - a.radius - b.radius;
    if (a.is_sphere() || b.is_sphere()) {
        const CollisionShape& sphere = a.is_sphere() ? a : b;
        const CollisionShape& hull = a.is_sphere() ? b : a;
        const Transform T = world_transform(a.is_sphere() ? pb : pa);
        const Vec3d centre = a.is_sphere() ? pa.x : pb.x;
        return nearest_on_hull(*hull.hull, T.R.transposed() * (centre - T.x)).distance - sphere.radius;
    }
    const Transform TA = world_transform(pa), TB = world_transform(pb);
    const Transform b_in_a = relative_transform(TA, TB), a_in_b = relative_transform(TB, TA);
    const double faces = std::max(query_faces(*a.hull, *b.hull, b_in_a, kInf).separation,
                                  query_faces(*b.hull, *a.hull, a_in_b, kInf).separation);
    return std::max(faces, query_edges(a, b, b_in_a, kInf).separation);
}

}  // namespace softbody
