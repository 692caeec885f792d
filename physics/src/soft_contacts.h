// Internal to the physics library: soft bodies against one another, and a body against itself
// (self_collision): every particle of a soft body against the triangles of every other soft
// body's surface, or, where a body has no faces (a point cloud), against its particles.
//
// The contact model: a point against a thick triangle. A particle stays at least the contact
// distance d from the nearest point of the other surface (d = kSurfaceThickness for a
// triangle, plus the particle's radius; a point cloud's particles are balls of half their
// usual spacing). Speculative, as the rigid contacts are: the pairs are found once a tick
// within how far their particles can move in it (a bounding-volume tree per body, refit every
// tick: bvh.h; or the last search's pairs again, while they cover this tick), and each substep
//   begin_substep  the nearest point and its normal where the substep begins (before the
//                  integrator): n points from the surface toward the particle, and stays
//                  fixed for the substep, so that a particle that would cross the surface in
//                  this step is still pushed back the way it came. Of each particle's
//                  triangles in reach it keeps the nearest (and the nearest across it, between
//                  two layers of a sheet): chosen where the tick begins, and anew every substep
//                  once the particle or those triangles have moved more than 1% of d since
//   solve          after the integrator's free step: impulses along n (Eq. 38 with the
//                  particle as body 1, no rotation term; body 2 the surface point, whose
//                  inverse mass is sum w_i^2 / m_i over its three particles) so that the gap
//                  at the step's end is not below d; with restitution for impacts, and
//                  Coulomb friction in impulse form (Eq. 24, 25: the tangential impulse that
//                  would stop the slide when within mu_s lambda, else mu_d lambda against the
//                  slide). The particle takes J, the surface's particles -w_i J: momentum is
//                  kept exactly. Then the positions move on by h times the velocity the
//                  impulses changed (and Verlet's step with them), as contact_solver.h does.
// Why this and not a continuous test: with the normal fixed where the substep begins and the
// gap measured where the free step ends, a particle is stopped at the surface however fast it
// comes (it can only close the gap it had), which is what a continuous test buys, at the cost
// of one nearest-point query per pair and substep. And a body resting on another rests: the
// gap each substep's gravity closes is exactly what the impulse takes away (the target is a
// gap of zero at the step's end), so nothing jitters and nothing creeps in.
// The geometry it asks (a triangle's nearest point, which way is out of a closed surface, the
// winding number, a hull's points) is triangle_queries.h's, with the other collision queries.
// What it does not catch: two edges crossing with no particle near the other's surface
// (coarse meshes, edge on edge). Meshes with particles a few thicknesses apart do not show it.
//
// Rigid shapes against a soft body's triangles, the same way: a sphere's centre (a point with
// the sphere's radius) and a hull's vertices and points along its edges (every 10 cm) against
// the triangles, found with the soft pairs,
// solved with them, Eq. 38 with the rigid body's full denominator (its J_world^-1 and arm r);
// the impulse changes its P and L, and its centre and turn follow by h times what they changed.
// So a ball smaller than the gaps between a coarse sheet's particles lands on the sheet, and a
// box's edge holds a soft face that overhangs it. (A soft particle against a rigid shape stays
// particle_contacts.h's, solved by contact_solver.h.)
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <span>

#include "bvh.h"
#include "physics/contact.h"
#include "physics/defs.h"
#include "physics/rigid_body.h"
#include "physics/soft_body.h"
#include "physics/thread_pool.h"
#include "triangle_queries.h"

namespace softbody {

// m: how thick a soft body's surface is for contacts (the gap two touching bodies keep).
inline constexpr float kSurfaceThickness = 0.005f;

class SoftContacts {
public:
    // Each body's surface (its triangles on its simulated particles), or for a body without
    // faces its particles' radius; the trees. Call whenever the bodies are built.
    void build(const std::vector<SoftBody>& bodies);
    // The pairs within reach over the tick of dt, found where the bodies are as it begins
    // (or the last search's, when it reached far enough to cover this tick too)
    // (call before body.x_tick_prev is overwritten: the last tick's motion says how far the
    // particles may go in this one). Returns whether there are any.
    // `rigid`, `state`: the rigid bodies and Listing 10's flat state as the tick begins.
    // The particles' queries run on the pool's threads, each chunk of particles into a list
    // of its own, joined in order: the same pairs in the same order at any thread count.
    bool find(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<const double> state,
              const WorldSettings& world, double dt, ThreadPool& pool);
    bool empty() const { return pairs_.empty(); }
    // Before the integrator moves the particles: each kept pair's nearest point and normal.
    // (Each particle's pairs on the pool's threads, in spans of whole particles, joined in order.)
    void begin_substep(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<const double> state,
                       ThreadPool& pool);
    // After the integrator's free step of h (and the rigid contacts): the impulses, on the
    // particles and on the rigid bodies' state.
    void solve(std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<double> state, const WorldSettings& world,
               float h);
    // The contacts of the last substep that pushed (lambda > 0), for display and the tests.
    const std::vector<SoftContact>& contacts() const { return touching_; }
    // f(r) for each rigid body r with a point within reach of a soft body's triangles this tick
    // (found by find; once per point): such a body is kept awake (sleep.h).
    // touching[b] = 1 for every soft body b with a pair or a rigid point within reach this tick.
    void mark_touching(std::vector<std::uint8_t>& touching) const {
        for (const Pair& pair : pairs_) touching[pair.a] = touching[pair.b] = 1;
        for (const RigidPair& pair : rigid_pairs_) touching[pair.soft] = 1;
    }
    template <class F>
    void for_each_rigid_in_reach(F f) const {
        for (const RigidPair& pair : rigid_pairs_) f(pair.rigid);
    }

private:
    // The surface's triangles and shape (triangle_queries.h). A closed one has an inside: its
    // contacts are signed (make_contact, by outward() and inside()). `orient` says which way its winding faces this tick:
    // +1 out, -1 in (the file winds it inward, or the body has been crushed through itself and
    // come out mirrored: its springs, every pair's, hold a mirror image as well as the shape),
    // 0 while it is squashed nearly flat (a quarter of its volume at rest or less: no inside
    // worth the name; its contacts are two-sided).
    struct Surface : TriangleSurface {
        float radius = 0.0f;                   // of each particle: 0 with faces, else half the spacing
        Bvh tree;                              // over the triangles, or over the particles without faces
        std::vector<Box3f> boxes;
    };
    struct Pair {
        std::uint32_t a, p, b, prim;  // particle p of body a against triangle (or particle) prim of body b
        float distance;               // d
        float found_at = 0.0f;        // the nearest point's distance where the tick began, m
        float reach = 0.0f;           // how far the two sides can close in the tick, m
        Vec3 away;                    // from the nearest point to the particle, where the tick began
        bool inside = false;          // found inside a closed surface, farther from it than its reach
    };
    struct Active {
        SoftContact c;
        float inv_mass_sum = 0.0f;    // Eq. 38's denominator: 1/m_p + sum w_i^2 / m_i
        float target = 0.0f;          // the least normal velocity the step may end with, m/s
        float bounce = 0.0f;          // closing speed as the substep began, m/s (> 0: closing)
        Vec3 friction;                // accumulated tangential impulse
        std::uint32_t slot[4] = {0, 0, 0, 0};  // solve's slots of the particle and the triangle's corners
    };
    // Particles, or pairs, a task of the pool takes: enough to outweigh waking a thread.
    static constexpr std::size_t kChunk = 1024;
    void prim_points(const Pair& pair, std::uint32_t out[3]) const;
    void find_particle(const std::vector<SoftBody>& bodies, std::size_t a, std::size_t b, std::uint32_t p, const Box3f& whole_b,
                       std::vector<Pair>& out) const;
    struct Near {
        std::uint32_t other[3];    // the triangle's corners (a particle three times)
        std::array<float, 3> w;    // the nearest point's weights
        Vec3 away;                 // from the nearest point to the particle
        float dist = 0.0f;         // |away|
        Vec3 way;                  // which way the normal points: away, or the face's on the face
        float inv_mass_sum = 0.0f;
    };
    bool nearest(const std::vector<SoftBody>& bodies, const Pair& pair, Near& out) const;
    // A particle of body a inside closed body b, farther in than its pairs reach: its pair
    // with b's nearest triangle (appended to out), or nothing when it is outside.
    void find_inside(const std::vector<SoftBody>& bodies, std::size_t a, std::size_t b, std::uint32_t p, float d,
                     std::vector<Pair>& out) const;
    void make_contact(const std::vector<SoftBody>& bodies, const Pair& pair, const Near& near, Active& c) const;
    // begin_substep's two halves: the rigid points' contacts, and one span of the particles'.
    void begin_rigid_substep(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid,
                             std::span<const double> state);
    void begin_span(const std::vector<SoftBody>& bodies, std::size_t span);

    // A rigid body's point (a sphere's centre, or a hull vertex) against a soft body's triangle.
    struct RigidPair {
        std::uint32_t rigid, feature, soft, tri;  // feature: the hull vertex (0 for a sphere)
        float side;  // +1: the point was on the side the triangle faces (its winding) as the tick began, -1 behind
        Vec3d local; // the point in body axes, from the centre of mass
    };
    struct RigidActive {
        std::uint32_t rigid = 0, soft = 0;
        Vec3d local;                 // the point in body axes, from the centre of mass
        double radius = 0.0;         // a sphere's; 0 for a vertex
        std::uint32_t other[3] = {0, 0, 0};
        float weight[3] = {0.0f, 0.0f, 0.0f};
        Vec3d n;                     // out of the triangle toward the rigid body
        double target = 0.0, bounce = 0.0, lambda = 0.0;
        Vec3d friction;
        Vec3d r;                     // arm from the centre of mass to the contact point, now
        double separation = 0.0;
        std::uint32_t slot[3] = {0, 0, 0};  // solve's slots of the triangle's corners
    };
    // find's stages, in its order (each says what it does where it is defined). `whole`: each
    // soft body's box, grown by how far its particles can go in the tick.
    void orient_surfaces(const std::vector<SoftBody>& bodies);
    std::vector<Box3f> reach_boxes(const std::vector<SoftBody>& bodies, float h, float g);
    void grow_rigid_boxes(std::span<const RigidBody> rigid, std::span<const double> state, double dt, float g);
    bool meets(const std::vector<SoftBody>& bodies, const std::vector<Box3f>& whole, std::size_t a, std::size_t b) const;
    bool meets_rigid(const std::vector<Box3f>& whole, std::size_t r, std::size_t b) const;
    bool can_reuse(const std::vector<SoftBody>& bodies, const std::vector<std::uint8_t>& meeting, bool rigid_meets) const;
    void refit_trees(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, const std::vector<Box3f>& whole,
                     ThreadPool& pool);
    void find_soft_pairs(const std::vector<SoftBody>& bodies, const std::vector<Box3f>& whole, ThreadPool& pool);
    void make_groups(const std::vector<SoftBody>& bodies);
    void find_rigid(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<const double> state,
                    const std::vector<Box3f>& whole, double dt, float g);
    void remember_search(const std::vector<SoftBody>& bodies, std::vector<std::uint8_t> meeting, bool rigid_meets);
    // solve's stages, in its order, and what they share: the compact copy of the velocities
    // (slot_of), the relative velocity and gap of a contact, an impulse applied.
    std::uint32_t slot_of(const std::vector<SoftBody>& bodies, std::uint32_t body, std::uint32_t i);
    void gather(const std::vector<SoftBody>& bodies);
    Vec3 relative(const Active& c) const;
    Vec3 position(const std::vector<SoftBody>& bodies, const Active& c) const;
    void push(std::uint32_t slot, const Vec3& impulse);
    void apply(const Active& c, const Vec3& J);
    void set_targets(const std::vector<SoftBody>& bodies, float e, float bounce_speed, float h);
    Vec3d rigid_relative(std::span<const RigidBody> rigid, const RigidActive& c) const;
    double rigid_denominator(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, const RigidActive& c,
                             const Vec3d& u) const;
    void rigid_apply(std::span<const RigidBody> rigid, const RigidActive& c, const Vec3d& J);
    void set_rigid_targets(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, std::span<const double> state,
                           float e, float bounce_speed, float h);
    void rigid_pass(const std::vector<SoftBody>& bodies, std::span<const RigidBody> rigid, float mu_s, float mu_d);
    void soft_pass(float mu_s, float mu_d);
    float pass_change(std::span<const RigidBody> rigid) const;
    void move_rigid(std::span<const RigidBody> rigid, std::span<double> state, float h) const;
    void scatter(std::vector<SoftBody>& bodies, bool verlet, float h);

    std::vector<RigidPair> rigid_pairs_;
    std::vector<RigidActive> rigid_active_;
    std::vector<Vec3d> dP_, dL_;     // per rigid body: what this substep's impulses added
    std::vector<Box3f> rigid_box_;   // per rigid body, as the tick began, grown by its reach
    std::vector<RigidMotion> motions_;  // per rigid body, after its free step (solve)
    std::vector<std::vector<Vec3d>> rigid_features_;  // per rigid body: its points, body axes (hull_feature)

    std::vector<Surface> surfaces_;
    std::vector<Pair> pairs_;
    std::vector<Active> active_;
    std::vector<std::vector<Pair>> chunk_pairs_;  // find's lists, one per chunk of particles
    std::vector<std::size_t> groups_;             // where each particle's pairs with a body begin in pairs_ (and the end)
    std::vector<std::size_t> spans_;              // begin_substep's spans of groups_: [spans_[k], spans_[k + 1])
    std::vector<std::array<std::uint32_t, 2>> choice_;  // per group: its nearest pair and the nearest across, + 1 (0: none)
    std::vector<std::uint8_t> moving_;            // per group: chosen anew every substep for the rest of the tick
    std::vector<std::uint32_t> corners_;          // per group: its triangles' corners, once each,
    std::vector<std::size_t> corners_begin_;      // from corners_[corners_begin_[g]] to corners_[corners_begin_[g + 1]]
    std::vector<std::array<std::uint32_t, 2>> touched_;  // the particles the groups' D reads: body, particle
    std::vector<Vec3> x_ref_;                     // each touched particle where the tick's first substep began
    std::vector<std::vector<float>> moved_;       // per body and particle: how far it has gone since, squared
    bool fresh_ = false;                          // find has run, no substep has begun since
    // find's last search: whether its pairs can serve again, which bodies met, each particle's
    // reach and position then.
    bool reusable_ = false;
    std::vector<std::uint8_t> meeting_found_;
    std::vector<std::vector<float>> reach_found_;
    std::vector<std::vector<Vec3>> x_found_;
    std::vector<std::vector<Active>> chunk_active_;  // begin_substep's contacts, one list per span
    std::vector<SoftContact> touching_;
    std::vector<std::vector<float>> reach_;   // per body, per particle: how far it can go in the tick
    // solve's compact copy: per body and particle its slot (kNoSlot: none); per slot the
    // particle's velocity, what the impulses added to it, its inverse mass, whose it is and
    // whether an impulse reached it.
    static constexpr std::uint32_t kNoSlot = ~0u;
    std::vector<std::vector<std::uint32_t>> slot_;
    std::vector<Vec3> local_v_, local_dv_;
    std::vector<Vec3> pass_v_;              // local_v_ as a pass began
    std::vector<Vec3d> pass_dP_, pass_dL_;  // dP_, dL_ as a pass began
    std::vector<float> local_im_;
    std::vector<std::array<std::uint32_t, 2>> local_of_;
    std::vector<std::uint8_t> local_pushed_;
};

}  // namespace softbody
