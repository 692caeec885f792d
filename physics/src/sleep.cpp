// Islands of rigid bodies and their sleep: World's members for it (sleep.h says what they do).
#include "sleep.h"

#include <algorithm>
#include <numeric>

#include "kept_memory.h"
#include "physics/world.h"
#include "soft_contacts.h"

namespace softbody {

namespace {

// Union-find over the rigid bodies, the lower index the root (so an island's root is its first
// body, whatever order the unions came in).
struct Islands {
    std::vector<std::uint32_t> parent;
    explicit Islands(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

}  // namespace

namespace {

// Each contact `sleeps` picks moved from `from` to the end of its island's list (`island_of`
// it), both kept in their order: a pass over the tick's contacts. A pile falling asleep at once
// (every contact leaving, into an island with none) takes the whole list without a copy: a
// pile's contacts are megabytes, and the fresh pages of such a copy made the tick stack:10 fell
// asleep in 2 ms longer than the ticks before it.
template <class Sleeps, class IslandOf>
void set_aside(std::vector<RigidContact>& from, std::vector<std::vector<RigidContact>>& islands, const Sleeps& sleeps,
               const IslandOf& island_of) {
    const auto list = [&](std::uint32_t island) -> std::vector<RigidContact>& {
        if (island >= islands.size()) islands.resize(std::size_t(island) + 1);
        return islands[island];
    };
    if (!from.empty() && sleeps(from.front())) {
        const std::uint32_t first = island_of(from.front());
        if (list(first).empty() &&
            std::all_of(from.begin(), from.end(), [&](const RigidContact& c) { return sleeps(c) && island_of(c) == first; })) {
            std::swap(from, islands[first]);
            return;
        }
    }
    std::size_t kept = 0;
    for (std::size_t k = 0; k < from.size(); ++k) {
        if (sleeps(from[k])) {
            list(island_of(from[k])).push_back(from[k]);
        } else {
            if (kept != k) from[kept] = from[k];
            ++kept;
        }
    }
    from.resize(kept);
}

}  // namespace

void World::reset_sleep() {
    sleep_.rest_time.assign(rigid_.size(), 0.0);
    sleep_.rest_pose.assign(rigid_.size() * kRestPoseSize, 0.0);
    sleep_.island.assign(rigid_.size(), kAwake);
    sleep_.deepest.assign(rigid_.size(), 0.0);
    sleep_.contacts.clear();
    sleep_.sleeping = 0;
    asleep_.assign(rigid_.size(), 0);
}

// Every body of the islands named wakes, its rest time back to 0; their contacts as they fell
// asleep go to `warm`, the contacts the solver warm-starts from.
void World::wake_islands(std::vector<std::uint32_t> islands, std::vector<RigidContact>& warm) {
    if (islands.empty() || sleep_.sleeping == 0) return;
    std::sort(islands.begin(), islands.end());
    islands.erase(std::unique(islands.begin(), islands.end()), islands.end());
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (!asleep_[b] || !std::binary_search(islands.begin(), islands.end(), sleep_.island[b])) continue;
        sleep_.island[b] = kAwake;
        sleep_.rest_time[b] = 0.0;
        asleep_[b] = 0;
        --sleep_.sleeping;
        if (b < motion_.size()) motion_[b] = rigid_motion(b);  // awake from now on (motion_)
    }
    // Their islands' contacts go, island after island (a pair's points are all in one island,
    // next to each other, in their order); no other island's are touched. One island waking into
    // an empty list is handed over whole.
    for (const std::uint32_t island : islands) {
        if (island >= sleep_.contacts.size()) continue;
        std::vector<RigidContact>& list = sleep_.contacts[island];
        if (warm.empty()) {
            std::swap(warm, list);
        } else {
            warm.insert(warm.end(), list.begin(), list.end());
        }
        list.clear();
    }
}

namespace {

// Whether the particle of a particle's contact comes at its rigid body: into its surface as fast
// as a body's point that is not at rest (kSleepSpeed). A soft body never sleeps, but one resting
// on rigid bodies neither keeps them awake nor wakes them: its particles lie on them as on fixed
// bodies while they sleep (the solver takes a sleeping body as static: contact_solver.h), and
// only one coming in (a landing, a push) wakes them. A particle merely rocking or sliding on the
// surface does not: a soft ball resting on a box rocks for seconds at a few cm/s.
bool particle_coming(const std::vector<SoftBody>& soft, const RigidContact& c) {
    return -dot(Vec3d(soft[std::size_t(c.soft)].v[c.a]), c.normal) >= kSleepSpeed;
}

}  // namespace

void World::wake_rigid(std::size_t i) {
    if (i < rigid_.size() && asleep_[i]) wake_islands({sleep_.island[i]}, contacts_);
}

void World::wake_all() {
    if (sleep_.sleeping == 0) return;
    std::vector<std::uint32_t> islands;
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (asleep_[b]) islands.push_back(sleep_.island[b]);
    }
    wake_islands(std::move(islands), contacts_);
}

// After contacts are found: a sleeping body in one of them met an awake body or a particle coming at it
// (contacts between two sleeping bodies, or a sleeping body and a fixed one or the ground, are
// never made), so its island wakes. The woken islands' contacts go to the last tick's list, which
// the solver warm-starts from. True when any woke: their contacts are to be found now.
bool World::wake_touched_islands() {
    if (sleep_.sleeping == 0) return false;
    // Each contact on its own, on every thread; the islands to wake are a set (wake_islands sorts
    // them), so the chunks' lists join in any order.
    std::vector<std::vector<std::uint32_t>> touched(std::size_t(4 * pool_->threads()));
    for_chunks(pool_.get(), contacts_.size(), 512, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkList taken(touched[chunk]);
        for (std::size_t k = begin; k < end; ++k) islands_touched(contacts_[k], *taken);
    });
    std::vector<std::uint32_t> islands;
    for (const std::vector<std::uint32_t>& some : touched) islands.insert(islands.end(), some.begin(), some.end());
    if (islands.empty()) return false;
    wake_islands(std::move(islands), previous_contacts_);
    return true;
}

// The sleeping islands contact c wakes, onto `out`.
void World::islands_touched(const RigidContact& c, std::vector<std::uint32_t>& out) const {
    const double dt = settings_.dt;
    const bool rigid_pair = c.soft < 0 && c.b >= 0 && !rigid_[c.a].fixed && !rigid_[std::size_t(c.b)].fixed;
    if (rigid_pair && asleep_[c.a] != asleep_[std::size_t(c.b)]) {
        // Between two rigid bodies, one awake: how far its point comes at the other in the
        // tick, from its velocity as the tick begins and the weight along the normal (n
        // points out of b toward a).
        const bool a_awake = !asleep_[c.a];
        const Vec3d arm = a_awake ? c.arm_a : c.arm_b;
        const RigidMotion m = rigid_motion(a_awake ? c.a : std::size_t(c.b));
        const double toward = a_awake ? -1.0 : 1.0;  // the awake side closes the gap moving along toward * n
        const double approach = toward * dot(m.v + cross(m.omega, arm), c.normal);
        const double fall = toward * dot(Vec3d(settings_.gravity), c.normal);
        const double reach = std::max(approach, 0.0) * dt + 0.5 * std::max(fall, 0.0) * dt * dt;
        if (c.separation - reach > kSleepTouch) return;  // it stays asleep: static to the awake one
    }
    if (c.soft < 0 && asleep_[c.a]) out.push_back(sleep_.island[c.a]);
    if (c.b >= 0 && asleep_[std::size_t(c.b)] && (c.soft < 0 || particle_coming(soft_, c))) out.push_back(sleep_.island[std::size_t(c.b)]);
}

// At the end of a tick: each awake body's rest time, the islands, and those that fall asleep.
void World::update_sleep() {
    const std::size_t n = rigid_.size();
    if (n == 0) return;
    const double dt = settings_.dt;
    // Bodies still being pushed out of an overlap deeper than a loaded contact stands: their
    // deepest contact deeper than kSleepDepth and shallower than a tick ago by kSleepDepthShrink.
    // On every thread (a pile's contacts are tens of megabytes). A body's deepest only ever
    // rises, to a contact's depth strictly above it, so it ends as the largest whatever order the
    // threads take its contacts in (and +0 when none is deeper than that, as it starts). (The
    // compilers' atomic built-ins: the browser build's C++ library has no std::atomic_ref.)
    // On one thread a plain compare does (a compare-and-swap costs several times as much).
    std::vector<double> deepest(n, 0.0);
    const bool shared = pool_->threads() > 1;
    const auto deepen = [shared](double& at, double depth) {
        if (!shared) {
            if (depth > at) at = depth;
            return;
        }
        double now;
        __atomic_load(&at, &now, __ATOMIC_RELAXED);
        while (depth > now && !__atomic_compare_exchange(&at, &now, &depth, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
        }
    };
    for_chunks(pool_.get(), contacts_.size(), 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const RigidContact& c = contacts_[k];
            if (c.soft >= 0) continue;
            deepen(deepest[c.a], c.depth);
            if (c.b >= 0) deepen(deepest[std::size_t(c.b)], c.depth);
        }
    });
    std::vector<std::uint8_t> overlapping(n, 0);
    for (std::size_t b = 0; b < n; ++b) {
        if (asleep_[b]) continue;
        overlapping[b] = deepest[b] > kSleepDepth && deepest[b] < sleep_.deepest[b] - kSleepDepthShrink ? 1 : 0;
        sleep_.deepest[b] = deepest[b];
    }
    // Each body's own rest time, on every thread: it starts when every point is slower than
    // kSleepSpeed, where the body is then, and goes on while no point has gone further than
    // kSleepDrift from there or faster than kTwitchSpeed.
    for_chunks(pool_.get(), n, 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            if (rigid_[b].fixed || asleep_[b]) continue;
            const RigidMotion& m = motion_[b];
            const double r = rigid_[b].bounding_radius;
            const double speed = length(m.v) + length(m.omega) * r;
            double* pose = &sleep_.rest_pose[b * kRestPoseSize];
            double& rest = sleep_.rest_time[b];
            if (overlapping[b]) {
                rest = 0.0;
            } else if (rest > 0.0 && speed < kTwitchSpeed) {
                // How far its points went: the centre's move, and the turn's at the body's reach
                // (the angle between the two orientations, 2 asin of the turn's vector part).
                const Quat q0{pose[3], pose[4], pose[5], pose[6]};
                const Quat turn = q0.conjugate() * m.q.normalized();
                const double half = std::min(1.0, std::sqrt(turn.x * turn.x + turn.y * turn.y + turn.z * turn.z));
                const double drift = length(m.x - Vec3d{pose[0], pose[1], pose[2]}) + 2.0 * std::asin(half) * r;
                rest = drift <= kSleepDrift ? rest + dt : 0.0;
            } else {
                rest = 0.0;
            }
            if (rest == 0.0 && speed < kSleepSpeed && !overlapping[b]) {
                rest = dt;
                const Quat q = m.q.normalized();
                const double start[kRestPoseSize] = {m.x.x, m.x.y, m.x.z, q.w, q.x, q.y, q.z};
                std::copy(start, start + kRestPoseSize, pose);
            }
        }
    });
    bool any_rested = false;
    for (std::size_t b = 0; b < n && !any_rested; ++b) any_rested = !rigid_[b].fixed && !asleep_[b] && sleep_.rest_time[b] >= kTimeToSleepReached;
    if (!settings_.sleeping || !any_rested) return;

    // The islands of the awake bodies, what leans on something fixed, and what is held.
    Islands islands(n);
    std::vector<std::uint8_t> supported(n, 0), held(n, 0);
    const auto dynamic = [&](std::int64_t b) { return b >= 0 && !rigid_[std::size_t(b)].fixed; };
    for (const RigidContact& c : contacts_) {
        if (c.soft >= 0) {
            if (c.b >= 0 && particle_coming(soft_, c)) held[std::size_t(c.b)] = 1;  // a particle coming at it
        } else if (dynamic(c.b)) {
            if (c.depth >= -kSleepTouch || c.normal_impulse > 0.0) islands.unite(c.a, std::uint32_t(c.b));
        } else {
            supported[c.a] = 1;  // the ground, or a fixed body
        }
    }
    if (soft_touching_) soft_contacts_->for_each_rigid_in_reach([&](std::uint32_t r) { held[r] = 1; });
    for (const Link& link : links_) {
        const LinkEnd* ends[2] = {&link.a, &link.b};
        for (int e = 0; e < 2; ++e) {
            const LinkEnd& end = *ends[e];
            const LinkEnd& other = *ends[1 - e];
            if (end.kind != LinkEnd::Kind::Rigid || !dynamic(end.body)) continue;
            if (other.kind == LinkEnd::Kind::Soft) held[end.body] = 1;
            else if (other.kind == LinkEnd::Kind::World || !dynamic(other.body)) supported[end.body] = 1;
            else islands.unite(end.body, other.body);
        }
    }
    if (grab_ && grab_->rigid && grab_->body < n) held[grab_->body] = 1;

    // An island sleeps when all its bodies have rested long enough, something fixed bears it,
    // and nothing that never sleeps holds it.
    std::vector<std::uint8_t> ready(n, 1), leans(n, 0);
    for (std::size_t b = 0; b < n; ++b) {
        if (rigid_[b].fixed || asleep_[b]) continue;
        const std::uint32_t root = islands.find(std::uint32_t(b));
        if (sleep_.rest_time[b] < kTimeToSleepReached || held[b]) ready[root] = 0;
        if (supported[b]) leans[root] = 1;
    }
    bool fell = false;
    for (std::size_t b = 0; b < n; ++b) {
        if (rigid_[b].fixed || asleep_[b]) continue;
        const std::uint32_t root = islands.find(std::uint32_t(b));
        if (!ready[root] || !leans[root]) continue;
        sleep_.island[b] = root;
        asleep_[b] = 1;
        ++sleep_.sleeping;
        double* y = &y_[b * rigid::kStateSize];
        for (int k = 0; k < 3; ++k) y[rigid::P + k] = y[rigid::L + k] = 0.0;
        fell = true;
    }
    if (!fell) return;
    // Their contacts are set aside, to warm-start the solver when they wake.
    set_aside(
        contacts_, sleep_.contacts, [&](const RigidContact& c) { return c.soft < 0 && asleep_[c.a] != 0; },
        [&](const RigidContact& c) { return sleep_.island[c.a]; });
}

}  // namespace softbody
