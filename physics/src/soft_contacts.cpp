#include "soft_contacts.h"

#include "ground_contact.h"
#include "kept_memory.h"
#include "triangle_queries.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace softbody {

namespace {

constexpr float kPushSpeed = 1.0f;     // m/s: the fastest an overlap is pushed apart (as contact_solver.h)
constexpr int kPasses = 8;             // at most, over every contact of a substep (Gauss-Seidel)
// A particle's choice of nearest triangle is kept while it moved, against the triangles in
// reach, by at most this part of the contact distance since the tick began (begin_substep).
constexpr float kKeepChoice = 0.01f;
// m: how much farther than its tick needs the search for pairs reaches, so that its pairs
// serve the ticks after it while the particles move less than that (find).
constexpr float kReuseMargin = 5e-4f;
constexpr float kSettled = 1e-5f;      // m/s: a pass that moves no velocity more than this ends them
// m: the gap a rigid shape keeps from a soft body's triangles. Thinner than kSurfaceThickness:
// the soft body's particles rest on the same shape at no gap (contact_solver.h), and the
// triangles between them should not stand off it by more than that.
constexpr double kRigidThickness = 0.001;

Box3f box_of(const Vec3& p, float grow) { return {p - Vec3{grow, grow, grow}, p + Vec3{grow, grow, grow}}; }

// Half the median distance from a particle to its nearest neighbour: the radius of a point
// cloud's particles (balls that just touch their neighbours). By a sweep along x: each
// particle looks at the particles after it in x order until the x gap alone is farther than
// the nearest found.
float cloud_radius(const Vec3Array& x) {
    const std::size_t n = x.size();
    if (n < 2) return kSurfaceThickness;
    std::vector<std::uint32_t> order(n);
    for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return x.x[a] < x.x[b] || (x.x[a] == x.x[b] && a < b); });
    std::vector<float> nearest(n, INFINITY);
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t i = order[k];
        for (std::size_t m = k + 1; m < n; ++m) {
            const std::uint32_t j = order[m];
            const float gap = x.x[j] - x.x[i];
            if (gap * gap >= nearest[i] && gap * gap >= nearest[j]) break;
            const Vec3 d = x[j] - x[i];
            const float d2 = dot(d, d);
            nearest[i] = std::min(nearest[i], d2);
            nearest[j] = std::min(nearest[j], d2);
        }
    }
    std::nth_element(nearest.begin(), nearest.begin() + std::ptrdiff_t(n / 2), nearest.end());
    const float r = 0.5f * std::sqrt(nearest[n / 2]);
    return std::isfinite(r) && r > 0.0f ? r : kSurfaceThickness;
}

}  // namespace

void SoftContacts::build(const std::vector<SoftBody>& bodies) {
    surfaces_.assign(bodies.size(), {});
    rigid_features_.clear();
    reach_.assign(bodies.size(), {});
    slot_.assign(bodies.size(), {});
    pairs_.clear();
    spans_.clear();
    reusable_ = false;
    active_.clear();
    touching_.clear();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const SoftBody& body = bodies[b];
        Surface& s = surfaces_[b];
        // The simulated particles' surface: the mesh's own, or a reduced body's particle mesh.
        const Mesh& mesh = body.reduced ? body.particle_mesh : body.mesh;
        for (const auto& t : particle_triangles(mesh)) {
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
            if (t[0] >= body.particle_count() || t[1] >= body.particle_count() || t[2] >= body.particle_count()) continue;
            s.triangles.insert(s.triangles.end(), t.begin(), t.end());
        }
        s.radius = s.triangles.empty() ? cloud_radius(body.rest) : 0.0f;
        slot_[b].assign(body.particle_count(), kNoSlot);
        close_surface(s, body.rest, body.particle_count());
    }
}

void SoftContacts::prim_points(const Pair& pair, std::uint32_t out[3]) const {
    const Surface& s = surfaces_[pair.b];
    if (s.triangles.empty()) {
        out[0] = out[1] = out[2] = pair.prim;
        return;
    }
    out[0] = s.triangles[3 * pair.prim];
    out[1] = s.triangles[3 * pair.prim + 1];
    out[2] = s.triangles[3 * pair.prim + 2];
}

// Particle p of body a against body b's triangles (or particles) within reach: appended to out,
// the nearest point first kept as found, then only the pairs that can matter (find says which).
void SoftContacts::find_particle(const std::vector<SoftBody>& bodies, std::size_t a, std::size_t b, std::uint32_t p,
                                 const Box3f& whole_b, std::vector<Pair>& out) const {
    const SoftBody& A = bodies[a];
    const SoftBody& B = bodies[b];
    const Surface& s = surfaces_[b];
    const bool faces = !s.triangles.empty();
    const float d = (faces ? kSurfaceThickness : s.radius) + surfaces_[a].radius;
    if (!whole_b.overlaps(box_of(A.x[p], reach_[a][p] + surfaces_[a].radius))) return;
    const std::size_t group = out.size();
    float nearest = INFINITY;
    Vec3 nearest_away;
    s.tree.query(box_of(A.x[p], reach_[a][p] + d), [&](std::uint32_t prim) {
        Pair pair{std::uint32_t(a), p, std::uint32_t(b), prim, d, 0.0f, 0.0f, {}};
        std::uint32_t v[3];
        prim_points(pair, v);
        if (a == b) {
            // Self contact: never a triangle the particle is a corner of, nor one it was
            // within reach of at rest (the same stretch of surface).
            if (v[0] == p || v[1] == p || v[2] == p) return;
            if (distance_to_triangle(A.rest[p], A.rest[v[0]], A.rest[v[1]], A.rest[v[2]]) < 2.0f * d) return;
        }
        // Within reach by the nearest point, not just by the boxes: a particle's box meets a
        // dozen small triangles of which one or two can matter.
        const float r = reach_[a][p] + std::max({reach_[b][v[0]], reach_[b][v[1]], reach_[b][v[2]]});
        pair.reach = r;
        if (faces) {
            const auto w = nearest_on_triangle(A.x[p], B.x[v[0]], B.x[v[1]], B.x[v[2]]);
            const Vec3 away = A.x[p] - (B.x[v[0]] * w[0] + B.x[v[1]] * w[1] + B.x[v[2]] * w[2]);
            const float distance = length(away);
            if (distance > d + r) return;
            if (distance < nearest) {
                nearest = distance;
                nearest_away = away;
            }
            pair.found_at = distance;
            pair.away = away;
        }
        out.push_back(pair);
    });
    // None within reach: inside a closed body, farther in than it can come out in the tick?
    if (faces && s.closed && s.orient != 0.0f && a != b && out.size() == group) {
        find_inside(bodies, a, b, p, d, out);
        return;
    }
    // A particle's contact with a surface is its nearest point, and the nearest on its other
    // side (begin_substep): of its triangles, only those that can come nearer in the tick than
    // the nearest one can go away, and those across it.
    if (faces && out.size() > group + 1) {
        std::size_t kept = group;
        for (std::size_t k = group; k < out.size(); ++k) {
            const Pair& q = out[k];
            if (q.found_at - q.reach <= nearest + q.reach || dot(q.away, nearest_away) < 0.0f) out[kept++] = q;
        }
        out.resize(kept);
    }
}

// A particle with no triangle of a closed body within reach may still be inside it (pushed in
// deeper than a tick's reach, or placed there): its nearest point on the whole surface, found
// by boxes twice as large each time until one holds a triangle, then every triangle nearer than
// the nearest found; inside when the way from that point to it is against the surface's
// outward direction there. Such a pair is kept whatever its distance (nearest(), below).
void SoftContacts::find_inside(const std::vector<SoftBody>& bodies, std::size_t a, std::size_t b, std::uint32_t p, float d,
                               std::vector<Pair>& out) const {
    const SoftBody& A = bodies[a];
    const SoftBody& B = bodies[b];
    const Surface& s = surfaces_[b];
    const Vec3 x = A.x[p];
    const Box3f& all = s.tree.bounds();
    if (x.x < all.lo.x || x.y < all.lo.y || x.z < all.lo.z || x.x > all.hi.x || x.y > all.hi.y || x.z > all.hi.z) return;
    const Vec3 size = all.hi - all.lo;
    const float most = length(size);
    float best = INFINITY;
    std::uint32_t best_tri = 0;
    std::array<float, 3> best_w{};
    const auto look = [&](float r) {
        s.tree.query(box_of(x, r), [&](std::uint32_t t) {
            const std::uint32_t* v = &s.triangles[3 * t];
            const auto w = nearest_on_triangle(x, B.x[v[0]], B.x[v[1]], B.x[v[2]]);
            const float dist = length(x - (B.x[v[0]] * w[0] + B.x[v[1]] * w[1] + B.x[v[2]] * w[2]));
            if (dist < best || (dist == best && t < best_tri)) {
                best = dist;
                best_tri = t;
                best_w = w;
            }
        });
    };
    for (float r = std::max(reach_[a][p] + d, 1e-3f); best == INFINITY && r < 2.0f * most; r *= 2.0f) look(r);
    if (best == INFINITY) return;
    look(best);  // the boxes that reached held the nearest only if it was within r; now every one within it
    const std::uint32_t* v = &s.triangles[3 * best_tri];
    const Vec3 away = x - (B.x[v[0]] * best_w[0] + B.x[v[1]] * best_w[1] + B.x[v[2]] * best_w[2]);
    if (!inside(s, B.x, best_tri, best_w, x, away)) return;
    Pair pair{std::uint32_t(a), p, std::uint32_t(b), best_tri, d, best, best + d, away};
    pair.inside = true;
    out.push_back(pair);
}

// Which way each closed surface faces this tick (Surface::orient): its volume now against its
// volume at rest; and which of its triangles are turned over (mark_turned: inside() asks the
// winding number beside them).
void SoftContacts::orient_surfaces(const std::vector<SoftBody>& bodies) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        Surface& s = surfaces_[b];
        if (!s.closed) continue;
        const double ratio = six_volume(s.triangles, bodies[b].x) / s.rest_volume;
        s.orient = std::abs(ratio) <= 0.25 ? 0.0f : float(ratio > 0.0 ? 1.0 : -1.0) * (s.rest_volume < 0.0 ? -1.0f : 1.0f);
        mark_turned(s, bodies[b].x);
    }
}

// How far each particle can go in the tick (as particle_contacts.h reckons it): at its speed,
// with gravity, twice what its last tick's forces added to the way it went, and a millimetre.
// Into reach_; returned, each body's box with it.
std::vector<Box3f> SoftContacts::reach_boxes(const std::vector<SoftBody>& bodies, float h, float g) {
    std::vector<Box3f> whole(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const SoftBody& body = bodies[b];
        std::vector<float>& reach = reach_[b];
        reach.resize(body.particle_count());
        for (std::size_t i = 0; i < body.particle_count(); ++i) {
            const Vec3 p = body.x[i];
            const float pushed = length(p - body.x_tick_prev[i] - body.v[i] * h);
            reach[i] = h * length(body.v[i]) + 2.0f * pushed + h * h * g + 1e-3f;
            const Box3f box = box_of(p, reach[i] + surfaces_[b].radius + kSurfaceThickness);
            if (i == 0) whole[b] = box;
            else whole[b].grow(box);
        }
    }
    return whole;
}

// Each rigid body's box where the tick begins, grown by how far it can move in it
// (speculative_margin, ground_contact.h): into rigid_box_.
void SoftContacts::grow_rigid_boxes(std::span<const RigidBody> rigid, std::span<const double> state, double dt, float g) {
    rigid_box_.resize(rigid.size());
    for (std::size_t r = 0; r < rigid.size(); ++r) {
        const RigidMotion m = rigid_motion(rigid[r], &state[r * rigid::kStateSize]);
        const double margin = rigid[r].fixed ? 0.0 : speculative_margin(rigid[r], m, dt, double(g));
        const float grow = float(rigid[r].bounding_radius + margin + kRigidThickness);
        rigid_box_[r] = box_of(to_float(m.x), grow);
    }
}

// Whether the particles of body a can reach body b in the tick, by their boxes `whole` (a == b:
// a body against itself, when it asks for that and has faces).
bool SoftContacts::meets(const std::vector<SoftBody>& bodies, const std::vector<Box3f>& whole, std::size_t a,
                         std::size_t b) const {
    if (a == b) return bodies[a].def.self_collision && !surfaces_[a].triangles.empty();
    return whole[a].overlaps(whole[b]);
}

// Whether rigid body r can reach body b's triangles in the tick.
bool SoftContacts::meets_rigid(const std::vector<Box3f>& whole, std::size_t r, std::size_t b) const {
    return !surfaces_[b].triangles.empty() && rigid_box_[r].overlaps(whole[b]);
}

// Whether the last search's pairs serve this tick too (find says when).
bool SoftContacts::can_reuse(const std::vector<SoftBody>& bodies, const std::vector<std::uint8_t>& meeting,
                             bool rigid_meets) const {
    bool reuse = reusable_ && !rigid_meets && meeting == meeting_found_ && x_found_.size() == bodies.size();
    for (std::size_t b = 0; b < bodies.size() && reuse; ++b) reuse = x_found_[b].size() == bodies[b].particle_count();
    float gone = 0.0f;  // squared
    for (std::size_t b = 0; b < bodies.size() && reuse; ++b) {
        for (std::size_t i = 0; i < bodies[b].particle_count(); ++i) {
            const Vec3 d = bodies[b].x[i] - x_found_[b][i];
            gone = std::max(gone, dot(d, d));
        }
    }
    gone = std::sqrt(gone);
    for (std::size_t b = 0; b < bodies.size() && reuse; ++b) {
        for (std::size_t i = 0; i < bodies[b].particle_count() && reuse; ++i) reuse = reach_[b][i] + gone <= reach_found_[b][i];
    }
    return reuse;
}

// Each body's tree refit where some body or rigid body can meet it, each body's on a thread of
// the pool (a tree is its body's alone).
void SoftContacts::refit_trees(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                               const std::vector<Box3f>& whole, ThreadPool& pool) {
    std::vector<std::uint32_t> refit;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        bool needed = false;
        for (std::size_t a = 0; a < bodies.size() && !needed; ++a) needed = meets(bodies, whole, a, b);
        for (std::size_t r = 0; r < rigid.size() && !needed; ++r) needed = meets_rigid(whole, r, b);
        if (needed) refit.push_back(std::uint32_t(b));
    }
    const auto fit = [&](std::size_t k) {
        const std::size_t b = refit[k];
        const SoftBody& body = bodies[b];
        Surface& s = surfaces_[b];
        const std::vector<float>& reach = reach_[b];
        const bool faces = !s.triangles.empty();
        const std::size_t count = faces ? s.triangles.size() / 3 : body.particle_count();
        s.boxes.resize(count);
        for (std::size_t t = 0; t < count; ++t) {
            if (!faces) {
                s.boxes[t] = box_of(body.x[t], reach[t]);
                continue;
            }
            const std::uint32_t* v = &s.triangles[3 * t];
            Box3f box = box_of(body.x[v[0]], reach[v[0]]);
            box.grow(box_of(body.x[v[1]], reach[v[1]]));
            box.grow(box_of(body.x[v[2]], reach[v[2]]));
            s.boxes[t] = box;
        }
        if (s.tree.empty()) s.tree.build(s.boxes);
        else s.tree.refit(s.boxes);
    };
    if (refit.size() == 1) fit(0);
    else if (refit.size() > 1) pool.run(refit.size(), fit);
}

// Each particle's pairs with a body it can meet, its particles in chunks spread over the
// threads, each chunk's pairs in a list of its own, joined in particle order afterwards: the
// pairs (and so every contact and impulse) come in the same order at any thread count.
void SoftContacts::find_soft_pairs(const std::vector<SoftBody>& bodies, const std::vector<Box3f>& whole, ThreadPool& pool) {
    for (std::size_t a = 0; a < bodies.size(); ++a) {
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            if (!meets(bodies, whole, a, b)) continue;
            // Two point clouds meet once, ball against ball; a body with faces meets a point
            // cloud particle against particle as well as the cloud's particles against its faces.
            if (surfaces_[b].triangles.empty() && surfaces_[a].triangles.empty() && b < a) continue;
            const std::uint32_t count = std::uint32_t(bodies[a].particle_count());
            const std::size_t chunks = (count + kChunk - 1) / kChunk;
            if (chunk_pairs_.size() < chunks) chunk_pairs_.resize(chunks);
            const auto run = [&](std::size_t k) {
                ChunkList taken(chunk_pairs_[k]);
                const std::uint32_t end = std::min<std::uint32_t>(count, std::uint32_t((k + 1) * kChunk));
                for (std::uint32_t p = std::uint32_t(k * kChunk); p < end; ++p) find_particle(bodies, a, b, p, whole[b], *taken);
            };
            if (chunks == 1) run(0);
            else pool.run(chunks, run);
            for (std::size_t k = 0; k < chunks; ++k) pairs_.insert(pairs_.end(), chunk_pairs_[k].begin(), chunk_pairs_[k].end());
        }
    }
}

// begin_substep's groups, one particle's pairs with one body each (its contacts are chosen
// among them), and its spans, whole groups of about kChunk pairs. Each group's choice is made
// anew in the tick's first substep.
void SoftContacts::make_groups(const std::vector<SoftBody>& bodies) {
    groups_.clear();
    spans_.assign(1, 0);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
        const Pair& p = pairs_[k];
        if (k > 0 && p.a == pairs_[k - 1].a && p.p == pairs_[k - 1].p && p.b == pairs_[k - 1].b) continue;
        if (k - (spans_.back() < groups_.size() ? groups_[spans_.back()] : k) >= kChunk) spans_.push_back(groups_.size());
        groups_.push_back(k);
    }
    if (!groups_.empty()) spans_.push_back(groups_.size());
    groups_.push_back(pairs_.size());
    choice_.assign(groups_.size() - 1, {0, 0});
    moving_.assign(groups_.size() - 1, 0);
    fresh_ = true;
    // Each group's corners, once each (its triangles share most), and the particles D reads
    // (the groups' particles and corners), once each.
    corners_.clear();
    corners_begin_.assign(1, 0);
    touched_.clear();
    moved_.resize(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) moved_[b].assign(bodies[b].particle_count(), -1.0f);
    const auto touch = [&](std::uint32_t b, std::uint32_t i) {
        if (moved_[b][i] == 0.0f) return;
        moved_[b][i] = 0.0f;
        touched_.push_back({b, i});
    };
    for (std::size_t group = 0; group + 1 < groups_.size(); ++group) {
        const Pair& first = pairs_[groups_[group]];
        const std::vector<std::uint32_t>& triangles = surfaces_[first.b].triangles;
        if (!triangles.empty()) {
            touch(first.a, first.p);
            const std::size_t from = corners_.size();
            for (std::size_t k = groups_[group]; k < groups_[group + 1]; ++k) {
                for (int j = 0; j < 3; ++j) {
                    const std::uint32_t v = triangles[3 * pairs_[k].prim + std::uint32_t(j)];
                    if (std::find(corners_.begin() + std::ptrdiff_t(from), corners_.end(), v) != corners_.end()) continue;
                    corners_.push_back(v);
                    touch(first.b, v);
                }
            }
        }
        corners_begin_.push_back(corners_.size());
    }
}

// Rigid shapes against the triangles: a sphere's centre, or each point of a hull (its vertices
// and points along its edges, hull_feature), against the triangles whose boxes its box meets
// (a query of the soft body's tree per point), kept when within reach by the nearest point.
// One point's triangles come together (begin_substep keeps its nearest).
void SoftContacts::find_rigid(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                              std::span<const double> state, const std::vector<Box3f>& whole, double dt, float g) {
    if (rigid_features_.size() != rigid.size()) rigid_features_.assign(rigid.size(), {});
    for (std::size_t r = 0; r < rigid.size(); ++r) {
        const RigidBody& body = rigid[r];
        const RigidMotion m = rigid_motion(body, &state[r * rigid::kStateSize]);
        const double margin = body.fixed ? 0.0 : speculative_margin(body, m, dt, double(g));
        std::vector<Vec3d>& features = rigid_features_[r];
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            if (!meets_rigid(whole, r, b)) continue;
            if (features.empty()) {  // made once: a rigid body's shape never changes
                if (body.hull) {
                    const std::uint32_t count = hull_feature_count(*body.hull);
                    for (std::uint32_t k = 0; k < count; ++k) features.push_back(hull_feature(*body.hull, k));
                } else {
                    features.push_back({});
                }
            }
            const SoftBody& B = bodies[b];
            const Surface& s = surfaces_[b];
            const double radius = body.hull ? 0.0 : body.radius;
            const float grow = float(radius + margin + kRigidThickness);
            for (std::uint32_t k = 0; k < features.size(); ++k) {
                const Vec3 p = to_float(m.x + m.R * features[k]);
                const Box3f point = box_of(p, grow);
                if (!point.overlaps(whole[b])) continue;
                s.tree.query(point, [&](std::uint32_t t) {
                    const std::uint32_t* v = &s.triangles[3 * t];
                    if (body.fixed && B.inv_mass[v[0]] == 0.0f && B.inv_mass[v[1]] == 0.0f && B.inv_mass[v[2]] == 0.0f) return;
                    const double reach = margin + double(std::max({reach_[b][v[0]], reach_[b][v[1]], reach_[b][v[2]]})) + kRigidThickness;
                    const auto w = nearest_on_triangle(p, B.x[v[0]], B.x[v[1]], B.x[v[2]]);
                    const Vec3 away = p - (B.x[v[0]] * w[0] + B.x[v[1]] * w[1] + B.x[v[2]] * w[2]);
                    if (double(length(away)) - radius > reach) return;
                    // Which side of the triangle the point is on (on it, within rounding: the
                    // side the triangle faces, outward for a closed body wound as files wind them).
                    const Vec3 face = cross(B.x[v[1]] - B.x[v[0]], B.x[v[2]] - B.x[v[0]]);
                    const float side = dot(away, face) < -1e-6f * length(face) ? -1.0f : 1.0f;
                    rigid_pairs_.push_back({std::uint32_t(r), k, std::uint32_t(b), t, side, features[k]});
                });
            }
        }
    }
}

// What the next tick needs to know of this search: whether its pairs can serve again, which
// bodies met, each particle's reach and position.
void SoftContacts::remember_search(const std::vector<SoftBody>& bodies, std::vector<std::uint8_t> meeting, bool rigid_meets) {
    // Not when rigid bodies are within reach (their points are found every tick), nor with a
    // particle inside a body (its nearest triangle is found again every tick).
    reusable_ = !rigid_meets && rigid_pairs_.empty() &&
                std::none_of(pairs_.begin(), pairs_.end(), [](const Pair& pair) { return pair.inside; });
    meeting_found_ = std::move(meeting);
    reach_found_ = reach_;
    x_found_.resize(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        x_found_[b].resize(bodies[b].particle_count());
        for (std::size_t i = 0; i < bodies[b].particle_count(); ++i) x_found_[b][i] = bodies[b].x[i];
    }
}

bool SoftContacts::find(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<const double> state,
                        const WorldSettings& world, double dt, ThreadPool& pool) {
    rigid_pairs_.clear();
    if (surfaces_.size() != bodies.size()) build(bodies);
    bool wanted = false, any_faces = false;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        wanted = wanted || bodies[b].def.self_collision;
        any_faces = any_faces || !surfaces_[b].triangles.empty();
    }
    const bool rigid_near = any_faces && !rigid.empty();
    if (bodies.size() < 2 && !wanted && !rigid_near) {
        pairs_.clear();
        spans_.clear();
        reusable_ = false;
        return false;
    }
    const float h = float(dt), g = length(world.gravity);
    orient_surfaces(bodies);
    std::vector<Box3f> whole = reach_boxes(bodies, h, g);
    grow_rigid_boxes(rigid, state, dt, g);
    // The last tick's pairs again, when no particle can reach anything this tick that the
    // search which found them did not cover: that search reached kReuseMargin farther than
    // its tick needed, from where the particles were then, and each particle's reach now plus
    // the farthest any particle has gone since is still within it (its box, the nearest-point
    // test and the choice among a particle's triangles all cover this tick's then). A body
    // resting on another moves micrometres a tick: its pairs are found once in many ticks.
    // Not with rigid bodies within reach (their points are found every tick, in the trees).
    std::vector<std::uint8_t> meeting(bodies.size() * bodies.size());
    for (std::size_t a = 0; a < bodies.size(); ++a) {
        for (std::size_t b = 0; b < bodies.size(); ++b) meeting[a * bodies.size() + b] = meets(bodies, whole, a, b) ? 1 : 0;
    }
    bool rigid_meets = false;
    for (std::size_t r = 0; r < rigid.size() && !rigid_meets; ++r) {
        for (std::size_t b = 0; b < bodies.size() && !rigid_meets; ++b) rigid_meets = meets_rigid(whole, r, b);
    }
    if (can_reuse(bodies, meeting, rigid_meets)) {
        choice_.assign(choice_.size(), {0, 0});
        moving_.assign(moving_.size(), 0);
        fresh_ = true;
        return !pairs_.empty();
    }
    // Found anew: kReuseMargin farther than this tick needs.
    pairs_.clear();
    spans_.clear();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        for (float& r : reach_[b]) r += kReuseMargin;
        whole[b] = {whole[b].lo - Vec3{kReuseMargin, kReuseMargin, kReuseMargin}, whole[b].hi + Vec3{kReuseMargin, kReuseMargin, kReuseMargin}};
    }
    refit_trees(bodies, rigid, whole, pool);
    find_soft_pairs(bodies, whole, pool);
    make_groups(bodies);
    find_rigid(bodies, rigid, state, whole, dt, g);
    remember_search(bodies, std::move(meeting), rigid_meets);
    return !pairs_.empty() || !rigid_pairs_.empty();
}

// One pair where the substep begins: the nearest point's weights and the way from it to the
// particle. False when out of reach for the rest of the tick, or when no impulse could move
// either side (every particle it weighs fixed). All that choosing among a particle's pairs
// needs; the rest only for the pairs chosen (make_contact).
bool SoftContacts::nearest(const std::vector<SoftBody>& bodies, const Pair& pair, Near& out) const {
    const SoftBody& A = bodies[pair.a];
    const SoftBody& B = bodies[pair.b];
    prim_points(pair, out.other);
    const Vec3 p = A.x[pair.p];
    const Vec3 x0 = B.x[out.other[0]], x1 = B.x[out.other[1]], x2 = B.x[out.other[2]];
    const bool point = out.other[0] == out.other[1];
    out.w = point ? std::array<float, 3>{1.0f, 0.0f, 0.0f} : nearest_on_triangle(p, x0, x1, x2);
    out.away = p - (x0 * out.w[0] + x1 * out.w[1] + x2 * out.w[2]);
    out.dist = length(out.away);
    // Within reach of this tick only (the pair was found for the whole of it).
    if (out.dist - pair.distance > pair.reach && !pair.inside) return false;
    if (point) out.w[1] = out.w[2] = 0.0f;
    float inv = A.inv_mass[pair.p];
    for (int k = 0; k < 3; ++k) inv += out.w[std::size_t(k)] * out.w[std::size_t(k)] * B.inv_mass[out.other[k]];
    if (!(inv > 0.0f)) return false;
    out.inv_mass_sum = inv;
    // Which way the normal points (make_contact): on the surface itself, the face's.
    out.way = out.dist > 1e-7f ? out.away : point ? Vec3{0.0f, 0.0f, 1.0f} : cross(x1 - x0, x2 - x0);
    return true;
}

// The contact of a chosen pair: its weights and normal, Eq. 38's denominator and the closing speed.
void SoftContacts::make_contact(const std::vector<SoftBody>& bodies, const Pair& pair, const Near& near, Active& c) const {
    const SoftBody& A = bodies[pair.a];
    const SoftBody& B = bodies[pair.b];
    c = Active{};
    c.c.body_a = pair.a;
    c.c.particle = pair.p;
    c.c.body_b = pair.b;
    for (int k = 0; k < 3; ++k) {
        c.c.other[k] = near.other[k];
        c.c.weight[k] = near.w[std::size_t(k)];
    }
    Vec3 n = near.away;
    float signed_dist = near.dist;
    const Surface& s = surfaces_[pair.b];
    if (s.closed && s.orient != 0.0f && pair.a != pair.b) {
        // A closed surface: the particle is outside or inside it, and the normal points out
        // of it either way; inside, the gap is minus the distance, and the push (at most
        // kPushSpeed) takes the particle out by the nearest way, not further in.
        if (near.dist > 1e-7f) {
            n = n / near.dist;
            if (inside(s, B.x, pair.prim, near.w, A.x[pair.p], near.away)) {
                n = -n;
                signed_dist = -near.dist;
            }
        } else {
            const Vec3 out = outward(s, B.x, pair.prim, near.w);
            const float l = length(out);
            n = l > 0.0f ? out / l : Vec3{0.0f, 0.0f, 1.0f};
        }
    } else if (near.dist > 1e-7f) {
        n = n / near.dist;
    } else {
        // On the surface itself: the face's normal (the way the face is wound).
        const float l = length(near.way);
        n = l > 0.0f ? near.way / l : Vec3{0.0f, 0.0f, 1.0f};
    }
    c.c.normal = Vec3d(n);
    c.c.separation = signed_dist - pair.distance;
    c.c.distance = pair.distance;
    // Eq. 38's denominator with body 2 the surface point: its velocity is sum w_i v_i, so an
    // impulse -J spread as -w_i J changes it by -sum w_i^2 J / m_i.
    c.inv_mass_sum = near.inv_mass_sum;
    Vec3 v_rel = A.v[pair.p];
    for (int k = 0; k < 3; ++k) v_rel -= B.v[c.c.other[k]] * c.c.weight[k];
    c.bounce = -dot(v_rel, n);
}

// Rigid points against triangles: the nearest triangle of each point (and the nearest across
// it), where the substep begins.
void SoftContacts::begin_rigid_substep(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                                       std::span<const double> state) {
    rigid_active_.clear();
    std::size_t rigid_group = 0;
    for (std::size_t k = 0; k < rigid_pairs_.size(); ++k) {
        const RigidPair& pair = rigid_pairs_[k];
        const RigidBody& body = rigid[pair.rigid];
        const SoftBody& B = bodies[pair.soft];
        const RigidMotion m = rigid_motion(body, &state[pair.rigid * rigid::kStateSize]);
        RigidActive c;
        c.rigid = pair.rigid;
        c.soft = pair.soft;
        const bool sphere = body.shape == ShapeKind::Sphere;
        c.local = pair.local;
        c.radius = sphere ? body.radius : 0.0;
        for (int j = 0; j < 3; ++j) c.other[j] = surfaces_[pair.soft].triangles[3 * pair.tri + std::uint32_t(j)];
        const Vec3d p = m.x + m.R * c.local;
        const Vec3d x0(B.x[c.other[0]]), x1(B.x[c.other[1]]), x2(B.x[c.other[2]]);
        const auto w = nearest_on_triangle(to_float(p), B.x[c.other[0]], B.x[c.other[1]], B.x[c.other[2]]);
        const Vec3d q = x0 * double(w[0]) + x1 * double(w[1]) + x2 * double(w[2]);
        // Over the face: its normal, on the point's side as the tick began (a point resting on
        // the face, or pushed a little through it, is still pushed back out the way it came).
        // Beyond an edge or a corner: from the nearest point to the point (a rounded edge).
        Vec3d n = normalize(cross(x1 - x0, x2 - x0)) * double(pair.side);
        double gap = dot(p - q, n);
        const double dist = length(p - q);
        // (More beside the edge than over the face: a point near the edge between two faces
        // would otherwise be pushed sideways by its small offset across the edge.)
        const double beside = length(p - q - n * gap);
        if ((w[0] == 0.0f || w[1] == 0.0f || w[2] == 0.0f) && beside > std::abs(gap) && dist > 1e-4) {
            n = (p - q) / dist;
            gap = dist;
        }
        c.n = n;
        c.separation = gap - c.radius - kRigidThickness;
        for (int j = 0; j < 3; ++j) c.weight[j] = w[std::size_t(j)];
        Vec3d v_rel = m.v + cross(m.omega, p - n * c.radius - m.x);
        for (int j = 0; j < 3; ++j) v_rel -= Vec3d(B.v[c.other[j]]) * double(c.weight[j]);
        c.bounce = -dot(v_rel, n);
        const bool same = k > 0 && rigid_pairs_[k - 1].rigid == pair.rigid && rigid_pairs_[k - 1].feature == pair.feature &&
                          rigid_pairs_[k - 1].soft == pair.soft;
        if (!same || rigid_active_.size() == rigid_group) {
            if (!same) rigid_group = rigid_active_.size();
            rigid_active_.push_back(c);
            continue;
        }
        RigidActive& best = rigid_active_[rigid_group];
        if (dot(c.n, best.n) >= 0.0) {
            if (c.separation < best.separation) best = c;
        } else if (rigid_active_.size() == rigid_group + 1) {
            rigid_active_.push_back(c);
        } else if (c.separation < rigid_active_[rigid_group + 1].separation) {
            rigid_active_[rigid_group + 1] = c;
        }
    }
}

// One span of find's groups (whole groups of one particle's pairs with one body): each group's
// contacts into the span's own list, the group's choice kept or made anew (begin_substep).
void SoftContacts::begin_span(const std::vector<SoftBody>& bodies, std::size_t span) {
    ChunkList taken(chunk_active_[span]);
    std::vector<Active>& out = *taken;
    Near near[2], next;
    for (std::size_t g = spans_[span]; g < spans_[span + 1]; ++g) {
        const std::size_t begin = groups_[g], end = groups_[g + 1];
        const Pair& first = pairs_[begin];
        const bool faces = !surfaces_[first.b].triangles.empty();
        const bool closed = surfaces_[first.b].closed && surfaces_[first.b].orient != 0.0f && first.a != first.b;
        if (faces && !fresh_ && !moving_[g]) {
            // D, against kKeepChoice d.
            const std::vector<float>& moved_b = moved_[first.b];
            float corner = 0.0f;
            for (std::size_t k = corners_begin_[g]; k < corners_begin_[g + 1]; ++k) corner = std::max(corner, moved_b[corners_[k]]);
            const float moved = std::sqrt(moved_[first.a][first.p]) + std::sqrt(corner);
            if (moved <= kKeepChoice * first.distance) {
                for (const std::uint32_t k : choice_[g]) {
                    if (k && nearest(bodies, pairs_[k - 1], next)) make_contact(bodies, pairs_[k - 1], next, out.emplace_back());
                }
                continue;
            }
            moving_[g] = 1;
        }
        // The group's choice: the nearest (same), and the nearest across it (across).
        std::uint32_t same = 0, across = 0;
        for (std::size_t k = begin; k < end; ++k) {
            const Pair& pair = pairs_[k];
            if (!nearest(bodies, pair, next)) continue;
            if (!faces) {  // a point cloud's balls: every one it touches
                make_contact(bodies, pair, next, out.emplace_back());
                continue;
            }
            if (!same) {
                same = std::uint32_t(k + 1);
                near[0] = next;
            } else if (closed) {
                // Signed: the nearest point alone says inside or out (make_contact).
                if (next.dist < near[0].dist) {
                    same = std::uint32_t(k + 1);
                    near[0] = next;
                }
            } else if (dot(Vec3d(next.way), Vec3d(near[0].way)) >= 0.0) {
                if (next.dist < near[0].dist) {
                    same = std::uint32_t(k + 1);
                    near[0] = next;
                }
            } else if (!across || next.dist < near[1].dist) {
                across = std::uint32_t(k + 1);
                near[1] = next;
            }
        }
        if (same) make_contact(bodies, pairs_[same - 1], near[0], out.emplace_back());
        if (across) make_contact(bodies, pairs_[across - 1], near[1], out.emplace_back());
        choice_[g] = {same, across};
    }
}

void SoftContacts::begin_substep(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                                 std::span<const double> state, ThreadPool& pool) {
    active_.clear();
    begin_rigid_substep(bodies, rigid, state);
    // One contact per particle and surface: its nearest triangle (the pairs of one particle and
    // body come one after another), and the nearest on the other side of the particle if there
    // is one (a particle between two layers of a folded sheet). The other triangles within
    // reach would only push along nearly the same normal, and cost the solver's passes.
    // Which triangle is nearest is chosen where the tick begins, and again in every substep
    // for a particle that has moved against the other surface since then: a particle sliding
    // fast crosses a small triangle in a tick. Moved by how much: each pair's distance changes
    // by at most D = |p - p_0| + max |x_i - x_i,0| (the particle's motion and the farthest
    // corner's among its triangles: the nearest point's weights on the moved corners are a
    // point at most that far from where it was), so while D <= kKeepChoice d the triangle
    // chosen is at most 2 D farther than the nearest, a gap 2% of the contact distance d off
    // at most; past that, the group is chosen anew every substep until the tick ends. The
    // chosen triangles' nearest points and normals are found anew every substep either way.
    // A body resting on another keeps its choice (its particles move micrometres in a tick)
    // and pays for one nearest point a contact, not one for every triangle in reach.
    // Each of find's spans (whole groups) on the pool's threads, its contacts into a list of
    // its own; the lists joined in span order: the same contacts in the same order at any
    // thread count.
    // Each touched particle where the tick's first substep began, then how far it has gone
    // since (squared).
    if (fresh_) {
        x_ref_.resize(touched_.size());
        for (std::size_t k = 0; k < touched_.size(); ++k) x_ref_[k] = bodies[touched_[k][0]].x[touched_[k][1]];
    } else {
        for (std::size_t k = 0; k < touched_.size(); ++k) {
            const auto [b, i] = touched_[k];
            const Vec3 d = bodies[b].x[i] - x_ref_[k];
            moved_[b][i] = dot(d, d);
        }
    }
    const std::size_t spans = spans_.empty() ? 0 : spans_.size() - 1;
    if (chunk_active_.size() < spans) chunk_active_.resize(spans);
    const auto make = [&](std::size_t span) { begin_span(bodies, span); };
    if (spans == 1) make(0);
    else if (spans > 1) pool.run(spans, make);
    fresh_ = false;
    for (std::size_t k = 0; k < spans; ++k) active_.insert(active_.end(), chunk_active_[k].begin(), chunk_active_[k].end());
}

// solve's compact copy of the velocities of the particles the contacts touch (gathered once,
// scattered back at the end): the same sums in the same order as on the bodies' own arrays,
// without their three separate streams per particle. A particle's slot, made on first use.
std::uint32_t SoftContacts::slot_of(const std::vector<SoftBody>& bodies, std::uint32_t body, std::uint32_t i) {
    std::uint32_t& slot = slot_[body][i];
    if (slot == kNoSlot) {
        slot = std::uint32_t(local_v_.size());
        local_v_.push_back(bodies[body].v[i]);
        local_dv_.push_back({});
        local_im_.push_back(bodies[body].inv_mass[i]);
        local_of_.push_back({body, i});
        local_pushed_.push_back(0);
    }
    return slot;
}

void SoftContacts::gather(const std::vector<SoftBody>& bodies) {
    for (Active& c : active_) {
        c.slot[0] = slot_of(bodies, c.c.body_a, c.c.particle);
        for (int k = 0; k < 3; ++k) c.slot[k + 1] = slot_of(bodies, c.c.body_b, c.c.other[k]);
    }
    for (RigidActive& c : rigid_active_) {
        for (int j = 0; j < 3; ++j) c.slot[j] = slot_of(bodies, c.soft, c.other[j]);
    }
}

// The particle's velocity less the surface point's, sum w_i v_i.
Vec3 SoftContacts::relative(const Active& c) const {
    Vec3 v = local_v_[c.slot[0]];
    for (int k = 0; k < 3; ++k) v -= local_v_[c.slot[k + 1]] * c.c.weight[k];
    return v;
}

// The way from the surface point to the particle, after the free step.
Vec3 SoftContacts::position(const std::vector<SoftBody>& bodies, const Active& c) const {
    const SoftBody& A = bodies[c.c.body_a];
    const SoftBody& B = bodies[c.c.body_b];
    Vec3 d = A.x[c.c.particle];
    for (int k = 0; k < 3; ++k) d -= B.x[c.c.other[k]] * c.c.weight[k];
    return d;
}

void SoftContacts::push(std::uint32_t slot, const Vec3& impulse) {
    const float im = local_im_[slot];
    if (im == 0.0f) return;
    const Vec3 dv = impulse * im;
    local_v_[slot] += dv;
    local_dv_[slot] += dv;
    local_pushed_[slot] = 1;
}

// J on the particle, -w_i J on the triangle's corners: momentum kept.
void SoftContacts::apply(const Active& c, const Vec3& J) {
    push(c.slot[0], J);
    for (int k = 0; k < 3; ++k) {
        if (c.c.weight[k] != 0.0f) push(c.slot[k + 1], J * -c.c.weight[k]);
    }
}

// Each contact's target: the normal velocity that brings its gap to zero at the step's end
// (the free step's gap over h, taken from its normal velocity; at most kPushSpeed apart where
// it overlapped already), or the bounce's -e v_n when it was hit faster than bounce_speed and
// meets the surface in this step.
void SoftContacts::set_targets(const std::vector<SoftBody>& bodies, float e, float bounce_speed, float h) {
    for (Active& c : active_) {
        const Vec3 n = to_float(c.c.normal);
        const float gap_free = dot(position(bodies, c), n) - float(c.c.distance);
        const float v_n = dot(relative(c), n);
        c.target = std::min(v_n - gap_free / h, kPushSpeed);
        if (gap_free < 0.0f && c.bounce > bounce_speed) c.target = std::max(c.target, e * c.bounce);
        c.c.normal_impulse = 0.0;
        c.friction = {};
    }
}

// A rigid point's velocity (its body's after the free step and this substep's impulses so far)
// less the surface point's.
Vec3d SoftContacts::rigid_relative(std::span<const RigidBody> rigid, const RigidActive& c) const {
    const RigidBody& body = rigid[c.rigid];
    const RigidMotion& m = motions_[c.rigid];
    const Vec3d v = m.v + dP_[c.rigid] * body.inv_mass, w = m.omega + m.J_inv * dL_[c.rigid];
    Vec3d u = v + cross(w, c.r);
    for (int j = 0; j < 3; ++j) u -= Vec3d(local_v_[c.slot[j]]) * double(c.weight[j]);
    return u;
}

// Eq. 38's denominator along a unit direction u: the rigid side's 1/m + u . ((J^-1 (r x u)) x r),
// the triangle's sum w_i^2 / m_i.
double SoftContacts::rigid_denominator(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                                       const RigidActive& c, const Vec3d& u) const {
    const RigidBody& body = rigid[c.rigid];
    const RigidMotion& m = motions_[c.rigid];
    double k = body.inv_mass + dot(u, cross(m.J_inv * cross(c.r, u), c.r));
    for (int j = 0; j < 3; ++j) k += double(c.weight[j] * c.weight[j] * bodies[c.soft].inv_mass[c.other[j]]);
    return k;
}

// J on the rigid body at its arm (Eq. 37), -w_i J on the triangle's corners.
void SoftContacts::rigid_apply(std::span<const RigidBody> rigid, const RigidActive& c, const Vec3d& J) {
    if (!rigid[c.rigid].fixed) {
        dP_[c.rigid] += J;
        dL_[c.rigid] += cross(c.r, J);  // Eq. 37
    }
    for (int j = 0; j < 3; ++j) {
        const std::uint32_t slot = c.slot[j];
        const float im = local_im_[slot];
        if (c.weight[j] == 0.0f || im == 0.0f) continue;
        const Vec3 dv = to_float(J * -double(c.weight[j] * im));
        local_v_[slot] += dv;
        local_dv_[slot] += dv;
        local_pushed_[slot] = 1;
    }
}

// Rigid points: each body's motion after its free step (and its own contacts), the arms and
// targets as for particles, with the body's restitution where it sets one.
void SoftContacts::set_rigid_targets(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                                     std::span<const double> state, float e, float bounce_speed, float h) {
    motions_.resize(rigid.size());
    dP_.assign(rigid.size(), {});
    dL_.assign(rigid.size(), {});
    for (std::size_t r = 0; r < rigid.size(); ++r) {
        if (!rigid_active_.empty()) motions_[r] = rigid_motion(rigid[r], &state[r * rigid::kStateSize]);
    }
    for (RigidActive& c : rigid_active_) {
        const RigidBody& body = rigid[c.rigid];
        const RigidMotion& m = motions_[c.rigid];
        const SoftBody& B = bodies[c.soft];
        const Vec3d p = m.x + m.R * c.local;
        c.r = p - c.n * c.radius - m.x;
        Vec3d q;
        for (int j = 0; j < 3; ++j) q += Vec3d(B.x[c.other[j]]) * double(c.weight[j]);
        const double gap_free = dot(p - q, c.n) - c.radius - kRigidThickness;
        const double v_n = dot(rigid_relative(rigid, c), c.n);
        c.target = std::min(v_n - gap_free / double(h), double(kPushSpeed));
        const double e_r = std::max(double(e), double(body.restitution.value_or(e)));
        if (gap_free < 0.0 && c.bounce > double(bounce_speed)) c.target = std::max(c.target, e_r * c.bounce);
        c.lambda = 0.0;
        c.friction = {};
    }
}

// One pass over the rigid points: Eq. 38 along n, then friction as for particles, along the
// slide, with its own denominator and the body's friction where it sets one.
void SoftContacts::rigid_pass(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, float mu_s, float mu_d) {
    for (RigidActive& c : rigid_active_) {
        const RigidBody& body = rigid[c.rigid];
        const double k_n = rigid_denominator(bodies, rigid, c, c.n);
        if (!(k_n > 0.0)) continue;
        const double v_n = dot(rigid_relative(rigid, c), c.n);
        const double lambda = std::max(0.0, c.lambda + (c.target - v_n) / k_n);
        const double dl = lambda - c.lambda;
        c.lambda = lambda;
        if (dl != 0.0) rigid_apply(rigid, c, c.n * dl);
        const double ms = body.friction ? double(*body.friction) : double(mu_s);
        const double md = body.friction ? double(*body.friction) : double(mu_d);
        const Vec3d v = rigid_relative(rigid, c);
        const Vec3d v_t = v - c.n * dot(v, c.n);
        const double slide = length(v_t);
        Vec3d total = c.friction;
        if (slide > 0.0) total -= v_t * (1.0 / rigid_denominator(bodies, rigid, c, v_t / slide));
        const double size = length(total);
        if (size > ms * lambda) total = size > 0.0 ? total * (md * lambda / size) : Vec3d{};
        const Vec3d df = total - c.friction;
        c.friction = total;
        if (df.x != 0.0 || df.y != 0.0 || df.z != 0.0) rigid_apply(rigid, c, df);
    }
}

// One pass over the particles' contacts.
void SoftContacts::soft_pass(float mu_s, float mu_d) {
    for (Active& c : active_) {
        const Vec3 n = to_float(c.c.normal);
        // Eq. 38 along n: lambda = (target - v_rel . n) / (1/m_1 + 1/m_2), summed and kept >= 0.
        Vec3 v = relative(c);
        const float v_n = dot(v, n);
        const float lambda = std::max(0.0f, float(c.c.normal_impulse) + (c.target - v_n) / c.inv_mass_sum);
        const float dl = lambda - float(c.c.normal_impulse);
        c.c.normal_impulse = lambda;
        // Friction (Eq. 24, 25 in impulse form): the tangential impulse that stops the slide,
        // kept whole while within mu_s lambda (static: it holds), else mu_d lambda against it.
        // The slide after the normal impulse: an impulse J on the contact (J on the particle,
        // -w_i J on the corners, four different particles) changes v_rel by J times Eq. 38's
        // denominator, so v_rel follows without gathering the velocities again, and both
        // impulses go out together.
        v += n * (dl * c.inv_mass_sum);
        const Vec3 v_t = v - n * dot(v, n);
        Vec3 total = c.friction - v_t / c.inv_mass_sum;
        const float size = length(total);
        if (size > mu_s * lambda) total = size > 0.0f ? total * (mu_d * lambda / size) : Vec3{};
        const Vec3 J = n * dl + (total - c.friction);
        c.friction = total;
        if (J.x != 0.0f || J.y != 0.0f || J.z != 0.0f) apply(c, J);
    }
}

// How far the pass that began at pass_v_ (pass_dP_, pass_dL_) moved any particle's velocity,
// or any rigid body's at its farthest point. Measured on the velocities, not on each contact's
// impulse: where two contacts hold the same particles (a particle of each body over the
// other's triangle, at the same spot), passes go on shifting the load from one to the other by
// as much as they like while no velocity moves, and the contacts' impulses would never say the
// passes are done.
float SoftContacts::pass_change(std::span<const RigidBody> rigid) const {
    float moved = 0.0f;
    for (std::size_t slot = 0; slot < local_v_.size(); ++slot) {
        const Vec3 d = local_v_[slot] - pass_v_[slot];
        moved = std::max(moved, dot(d, d));
    }
    moved = std::sqrt(moved);
    for (std::size_t r = 0; r < pass_dP_.size() && !rigid_active_.empty(); ++r) {
        const Vec3d dv = (dP_[r] - pass_dP_[r]) * rigid[r].inv_mass, dw = motions_[r].J_inv * (dL_[r] - pass_dL_[r]);
        moved = std::max(moved, float(length(dv) + length(dw) * rigid[r].bounding_radius));
    }
    return moved;
}

// A rigid body's momenta take the impulses; its centre and turn follow by h times the velocity
// and spin they changed (dv = dP / m, dw = J_world^-1 dL).
void SoftContacts::move_rigid(std::span<const RigidBody> rigid, std::span<double> state, float h) const {
    for (std::size_t r = 0; r < rigid.size(); ++r) {
        if (rigid[r].fixed || (dP_[r] == Vec3d{} && dL_[r] == Vec3d{})) continue;
        double* y = &state[r * rigid::kStateSize];
        const Vec3d dv = dP_[r] * rigid[r].inv_mass, dw = motions_[r].J_inv * dL_[r];
        for (int k = 0; k < 3; ++k) {
            y[rigid::P + k] += dP_[r][k];
            y[rigid::L + k] += dL_[r][k];
            y[rigid::X + k] += double(h) * dv[k];
        }
        const double angle = length(dw) * double(h);
        if (angle > 0.0) {
            const Quat q = Quat::from_axis_angle(dw / length(dw), angle) * Quat{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]};
            y[rigid::Q] = q.w;
            y[rigid::Q + 1] = q.x;
            y[rigid::Q + 2] = q.y;
            y[rigid::Q + 3] = q.z;
        }
    }
}

// The velocities back onto the bodies, and the positions follow the velocity the impulses
// changed: x += h dv (Verlet's step too). The compact copy emptied for the next substep.
void SoftContacts::scatter(std::vector<SoftBody>& bodies, bool verlet, float h) {
    for (std::size_t slot = 0; slot < local_v_.size(); ++slot) {
        const auto [b, i] = local_of_[slot];
        slot_[b][i] = kNoSlot;
        if (!local_pushed_[slot]) continue;
        SoftBody& body = bodies[b];
        const Vec3 dv = local_dv_[slot];
        body.v.set(i, local_v_[slot]);
        body.x.add(i, dv * h);
        if (verlet) body.verlet_step.add(i, dv * h);
    }
    local_v_.clear();
    local_dv_.clear();
    local_im_.clear();
    local_of_.clear();
    local_pushed_.clear();
}

void SoftContacts::solve(std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<double> state,
                         const WorldSettings& world, float h) {
    touching_.clear();
    if (active_.empty() && rigid_active_.empty()) return;
    const float e = world.restitution, mu_s = world.static_friction, mu_d = world.dynamic_friction;
    // As for the rigid contacts: impacts slower than two ticks' worth of gravity are resting contact.
    const float bounce_speed = 2.0f * length(world.gravity) * world.dt;
    gather(bodies);
    set_targets(bodies, e, bounce_speed, h);
    set_rigid_targets(bodies, rigid, state, e, bounce_speed, h);
    for (int pass = 0; pass < kPasses; ++pass) {
        // Where the pass starts, to say how far it moved each velocity (pass_change).
        pass_v_.assign(local_v_.begin(), local_v_.end());
        if (!rigid_active_.empty()) {
            pass_dP_.assign(dP_.begin(), dP_.end());
            pass_dL_.assign(dL_.begin(), dL_.end());
        }
        rigid_pass(bodies, rigid, mu_s, mu_d);
        soft_pass(mu_s, mu_d);
        // Converged: the pass moved no velocity by more than kSettled.
        if (pass_change(rigid) < kSettled) break;
    }
    move_rigid(rigid, state, h);
    scatter(bodies, world.integrator == Integrator::Verlet, h);
    for (const Active& c : active_) {
        if (c.c.normal_impulse <= 0.0) continue;
        SoftContact out = c.c;
        out.tangent_impulse = length(c.friction);
        out.impulse = c.c.normal * c.c.normal_impulse + Vec3d(c.friction);
        touching_.push_back(out);
    }
}

}  // namespace softbody
