// Time travel's half in the world (world.h): the state a tick carries into the next, copied
// out and put back, with what the world held at that moment.
#include <algorithm>
#include <stdexcept>

#include "rigid_contacts.h"
#include "soft_contacts.h"
#include "physics/world.h"

namespace softbody {

WorldSnapshot World::snapshot() const {
    WorldSnapshot out;
    for (const SoftBody& body : soft_) {
        out.soft.push_back({body.built, body.def, body.x, body.v, body.verlet_step, body.x_tick_prev, body.inv_mass, body.verlet_h});
    }
    out.soft_ids = soft_ids_;
    out.rigid_ids = rigid_ids_;
    out.spring_ids = spring_ids_;
    out.rigid_built = rigid_built_;
    out.rigid_defs = rigid_defs_;
    out.springs = spring_defs_;
    out.links = links_;
    out.rigid = y_;
    out.rigid_tick_prev = y_tick_prev_;
    out.contacts = contacts_;
    out.pair_cache = rigid_contact_scratch_->cache;
    out.ticks = ticks_;
    out.status = status_;
    out.divergence = divergence_;
    out.energy_baseline = energy_baseline_;
    out.energy_scale = energy_scale_;
    out.energy_baseline_stale = energy_baseline_stale_;
    out.sleep = sleep_;
    return out;
}

void World::restore(const WorldSnapshot& s) {
    if (s.soft.size() != s.soft_ids.size() || s.rigid.size() != s.rigid_ids.size() * rigid::kStateSize ||
        s.rigid.size() != s.rigid_tick_prev.size() || s.rigid_built.size() != s.rigid_ids.size() ||
        s.sleep.island.size() != s.rigid_ids.size() || s.sleep.rest_time.size() != s.sleep.island.size() ||
        s.sleep.rest_pose.size() != s.sleep.island.size() * kRestPoseSize ||
        s.links.size() != s.spring_ids.size()) {
        throw std::invalid_argument("World::restore: a snapshot that does not hold together");
    }
    const bool same_things = s.soft_ids == soft_ids_ && s.rigid_ids == rigid_ids_ && s.spring_ids == spring_ids_;
    if (!same_things) {
        // What the world held then: the bodies it still has keep theirs (their meshes, hulls and
        // kernels), the others are made again from their definitions, the springs are as they were.
        std::vector<SoftBody> soft;
        for (std::size_t k = 0; k < s.soft.size(); ++k) {
            const std::uint32_t now = soft_ids_.index(s.soft_ids.at(k));
            if (now != SoftBodyId::kNone) soft.push_back(std::move(soft_[now]));
            else soft.push_back(make_soft_body(s.soft[k].def, &s.soft[k].built));
        }
        std::vector<RigidBody> rigid;
        std::vector<RigidBodyDef> defs, built;
        std::vector<CollisionShape> shapes;
        for (std::size_t k = 0; k < s.rigid_built.size(); ++k) {
            const std::uint32_t now = rigid_ids_.index(s.rigid_ids.at(k));
            if (now != RigidBodyId::kNone) {
                rigid.push_back(std::move(rigid_[now]));
                defs.push_back(rigid_defs_[now]);
                built.push_back(rigid_built_[now]);
                shapes.push_back(std::move(shapes_[now]));
            } else {
                rigid.push_back(make_rigid_body(s.rigid_built[k]));
                rigid.back().restitution = s.rigid_defs[k].restitution;
                rigid.back().friction = s.rigid_defs[k].friction;
                rigid.back().color = s.rigid_defs[k].color;
                defs.push_back(s.rigid_defs[k]);
                built.push_back(s.rigid_built[k]);
                shapes.push_back(collision_shape(rigid.back()));
            }
        }
        soft_ = std::move(soft);
        rigid_ = std::move(rigid);
        rigid_defs_ = std::move(defs);
        rigid_built_ = std::move(built);
        shapes_ = std::move(shapes);
        spring_defs_ = s.springs;
        links_ = s.links;
        soft_ids_ = s.soft_ids;
        rigid_ids_ = s.rigid_ids;
        spring_ids_ = s.spring_ids;
        y_ = s.rigid;
        asleep_.assign(rigid_.size(), 0);
        structure_changed();
        if (grab_) grab_.reset();
    }
    for (std::size_t b = 0; b < s.soft.size(); ++b) {
        SoftBody& body = soft_[b];
        const WorldSnapshot::Soft& from = s.soft[b];
        if (from.x.size() != body.particle_count()) throw std::invalid_argument("World::restore: a snapshot of another body");
        body.x = from.x;
        body.v = from.v;
        body.verlet_step = from.verlet_step;
        body.x_tick_prev = from.x_tick_prev;
        body.inv_mass = from.inv_mass;
        body.verlet_h = from.verlet_h;
    }
    y_ = s.rigid;
    y_tick_prev_ = s.rigid_tick_prev;
    contacts_ = s.contacts;
    rigid_contact_scratch_->cache = s.pair_cache;  // its body indices are the snapshot's, as now
    previous_contacts_.clear();
    ticks_ = s.ticks;
    status_ = s.status;
    divergence_ = s.divergence;
    energy_baseline_ = s.energy_baseline;
    energy_scale_ = s.energy_scale;
    energy_baseline_stale_ = s.energy_baseline_stale;
    ++outside_changes_;  // the world jumped to another moment
    sleep_ = s.sleep;
    for (std::size_t b = 0; b < rigid_.size(); ++b) asleep_[b] = sleep_.island[b] != kAwake ? 1 : 0;
}

std::size_t WorldSnapshot::bytes() const {
    std::size_t total = sizeof(*this), sleeping_contacts = 0;
    for (const std::vector<RigidContact>& island : sleep.contacts) {
        total += sizeof(island);
        sleeping_contacts += island.size();
    }
    for (const Soft& body : soft) {
        total += sizeof(Soft) + body.inv_mass.size() * sizeof(float) + (body.def.pinned.size() + body.built.pinned.size()) * 4 +
                 (body.x.size() + body.v.size() + body.verlet_step.size() + body.x_tick_prev.size()) * 3 * sizeof(float);
    }
    return total + (rigid.size() + rigid_tick_prev.size() + sleep.rest_time.size() + sleep.rest_pose.size()) * sizeof(double) +
           (contacts.size() + sleeping_contacts) * sizeof(RigidContact) + pair_cache.pairs.size() * sizeof(CachedPair) +
           pair_cache.points.size() * sizeof(CachedPoint) + sleep.island.size() * sizeof(std::uint32_t) +
           (rigid_built.size() + rigid_defs.size()) * sizeof(RigidBodyDef) + springs.size() * sizeof(SpringDef) +
           links.size() * sizeof(Link) + divergence.size();
}

}  // namespace softbody
