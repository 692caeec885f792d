// What a world holds, made and unmade while it runs (world.h): soft bodies, rigid bodies and
// springs by definition, their ids and names, their keys, and the reset that builds them again.
// The tick itself is world.cpp's.
#include <algorithm>
#include <cmath>

#include "contact_solver.h"
#include "message_text.h"
#include "rigid_contacts.h"
#include "soft_contacts.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/world.h"

namespace softbody {

namespace {

void check_pins(const SoftBodyDef& def, const Mesh& mesh) {
    for (std::uint32_t vertex : def.pinned) {
        if (vertex >= mesh.vertex_to_particle.size()) {
            throw InputError("soft body '" + printable(def.name) + "': key 'pinned': vertex " + std::to_string(vertex) +
                             " does not exist (the mesh has " + std::to_string(mesh.vertex_to_particle.size()) +
                             " vertices, numbered from 0)");
        }
    }
}

// Keys that apply on reset differ between two definitions of the same kind.
template <class D>
bool reset_keys_differ(const D& a, const D& b, KeyOwner owner) {
    for (const KeyInfo* info : keys_of(owner)) {
        if (info->on_reset && !info->alias && !(get_key(a, *info) == get_key(b, *info))) return true;
    }
    return false;
}

// Removes the contacts of a destroyed body and renumbers those of the bodies after it.
void forget_body(std::vector<RigidContact>& contacts, bool rigid, std::uint32_t index) {
    std::erase_if(contacts, [&](const RigidContact& c) {
        if (rigid) return (c.soft < 0 && c.a == index) || c.b == std::int32_t(index);
        return c.soft == std::int32_t(index);
    });
    for (RigidContact& c : contacts) {
        if (rigid) {
            if (c.soft < 0 && c.a > index) --c.a;
            if (c.b > std::int32_t(index)) --c.b;
        } else if (c.soft > std::int32_t(index)) {
            --c.soft;
        }
    }
}

}  // namespace

World::World(const WorldDef& def, WorldOptions options)
    : settings_(def.settings),
      rigid_contact_scratch_(std::make_unique<RigidContactScratch>()),
      solver_(std::make_unique<ContactSolver>()),
      soft_contacts_(std::make_unique<SoftContacts>()),
      reference_kernel_(options.reference_kernel) {
    validate(settings_);
    pool_ = std::make_unique<ThreadPool>(std::max(1, options.threads));
    // Every body first (a spring names them), then one build of the whole.
    for (const SoftBodyDef& d : def.soft_bodies) {
        check_new_name(d.name);
        soft_.push_back(make_soft_body(d));
        soft_ids_.add();
    }
    for (const RigidBodyDef& d : def.rigid_bodies) {
        check_new_name(d.name);
        rigid_.push_back(make_rigid_body(d));
        rigid_defs_.push_back(d);
        rigid_built_.push_back(d);
        shapes_.push_back(collision_shape(rigid_.back()));
        rigid_ids_.add();
        notes_.insert(notes_.end(), rigid_.back().notes.begin(), rigid_.back().notes.end());
    }
    const std::size_t n = rigid_.size() * rigid::kStateSize;
    for (auto* y : {&y_, &y_tick_prev_, &y_good_, &y_stage_, &k_[0], &k_[1], &k_[2], &k_[3]}) y->assign(n, 0.0);
    link_force_on_rigid_.assign(rigid_.size(), {});
    link_torque_on_rigid_.assign(rigid_.size(), {});
    link_force_on_particles_.assign(soft_.size(), {});
    build();
    for (const SpringDef& d : def.springs) {
        if (!d.name.empty()) check_new_name(d.name);
        links_.push_back(resolve_link(d, d.name.empty() ? "spring " + std::to_string(links_.size() + 1) : "spring '" + printable(d.name) + "'"));
        spring_defs_.push_back(d);
        spring_ids_.add();
    }
    update_substeps();  // the links' springs count toward the step's stability
}

World::~World() = default;

// A soft body made from its definition (its mesh loaded, its particles built), or from `built`
// with the keys of `def` (a body restored from a snapshot). Throws InputError naming it.
SoftBody World::make_soft_body(const SoftBodyDef& def, const SoftBodyDef* built) {
    const SoftBodyDef& made = built ? *built : def;
    if (def.name.empty()) throw InputError("a soft body needs a \"name\"");
    validate(made);
    validate(def);
    SoftBody body;
    body.def = made;
    if (!body.def.geometry) {
        if (made.mesh.empty()) throw InputError("soft body '" + printable(def.name) + "' needs a \"mesh\"");
        try {
            body.def.geometry = std::make_shared<const Mesh>(open_mesh(made.mesh));
        } catch (const InputError& e) {
            rethrow_within("soft body '" + printable(def.name) + "': ", e);
        }
    }
    body.mesh = *body.def.geometry;
    if (body.mesh.positions.empty()) throw InputError(body.mesh.source + ": the mesh has no vertices");
    check_pins(made, body.mesh);
    check_pins(def, body.mesh);
    body.kernel = std::make_unique<PairForceKernel>(*pool_);
    build_particles(body);
    if (built) {
        body.def = def;
        body.def.geometry = body.built.geometry;
        apply_body_keys(body);
    }
    // What the loader set aside in the mesh file (a dangling normal index, ...), and a budget
    // that asked for every vertex and got fewer: a line each, not kept quiet.
    notes_.insert(notes_.end(), body.mesh.warnings.begin(), body.mesh.warnings.end());
    if (std::string note = particle_cap_note(body); !note.empty()) notes_.push_back(std::move(note));
    return body;
}

void World::check_new_name(const std::string& name) const {
    if (name.empty()) return;
    const bool taken = find_soft_body(name) || find_rigid_body(name) || find_spring(name);
    if (taken) throw InputError("two things are named '" + printable(name) + "'; names must be unique");
}

// The rest of the world follows a change of what it holds: the per-body arrays, the springs'
// ends (found again by name, their rest lengths kept), the soft contacts' surfaces.
void World::structure_changed() {
    const std::size_t n = rigid_.size() * rigid::kStateSize;
    for (auto* y : {&y_stage_, &k_[0], &k_[1], &k_[2], &k_[3]}) y->assign(n, 0.0);
    y_good_ = y_;
    link_force_on_rigid_.assign(rigid_.size(), {});
    link_torque_on_rigid_.assign(rigid_.size(), {});
    link_force_on_particles_.assign(soft_.size(), {});
    for (std::size_t s = 0; s < links_.size(); ++s) {
        const double l0 = links_[s].l0;
        links_[s] = resolve_link(spring_defs_[s], "spring");
        links_[s].l0 = l0;
    }
    soft_contacts_->build(soft_);
    soft_touching_ = false;
    solver_particles_.clear();
    solver_particle_v_.clear();
    changed_from_outside();
    update_substeps();
}

SoftBodyId World::create_soft_body(SoftBodyDef def) {
    check_new_name(def.name);
    SoftBody body = make_soft_body(def);
    soft_.push_back(std::move(body));
    const SoftBodyId id = soft_ids_.add();
    structure_changed();
    return id;
}

RigidBodyId World::create_rigid_body(const RigidBodyDef& def) {
    check_new_name(def.name);
    RigidBody body = make_rigid_body(def);
    notes_.insert(notes_.end(), body.notes.begin(), body.notes.end());
    shapes_.push_back(collision_shape(body));
    rigid_.push_back(std::move(body));
    rigid_defs_.push_back(def);
    rigid_built_.push_back(def);
    // Its thirteen numbers as it starts; the others go on from where they are.
    const auto& start = rigid_.back().initial;
    for (auto* y : {&y_, &y_tick_prev_}) y->insert(y->end(), start.begin(), start.end());
    sleep_.rest_time.push_back(0.0);
    sleep_.rest_pose.insert(sleep_.rest_pose.end(), kRestPoseSize, 0.0);
    sleep_.island.push_back(kAwake);
    sleep_.deepest.push_back(0.0);
    asleep_.push_back(0);
    const RigidBodyId id = rigid_ids_.add();
    structure_changed();
    return id;
}

SpringId World::create_spring(const SpringDef& def) {
    if (!def.name.empty()) check_new_name(def.name);
    links_.push_back(resolve_link(def, def.name.empty() ? "spring" : "spring '" + printable(def.name) + "'"));
    spring_defs_.push_back(def);
    const SpringId id = spring_ids_.add();
    wake_all();
    update_substeps();
    changed_from_outside();
    return id;
}

void World::destroy(SpringId id) {
    const std::size_t s = index(id);
    links_.erase(links_.begin() + std::ptrdiff_t(s));
    spring_defs_.erase(spring_defs_.begin() + std::ptrdiff_t(s));
    spring_ids_.remove(id);
    wake_all();
    update_substeps();
    changed_from_outside();
}

void World::destroy(SoftBodyId id) {
    const std::size_t b = index(id);
    const std::string name = soft_[b].name();
    for (std::size_t s = links_.size(); s-- > 0;) {
        if (spring_defs_[s].a.body == name || spring_defs_[s].b.body == name) destroy(spring_ids_.at(s));
    }
    wake_all();
    soft_.erase(soft_.begin() + std::ptrdiff_t(b));
    soft_ids_.remove(id);
    forget_body(contacts_, false, std::uint32_t(b));
    forget_body(previous_contacts_, false, std::uint32_t(b));
    if (grab_ && !grab_->rigid) {
        if (grab_->body == b) grab_.reset();
        else if (grab_->body > b) --grab_->body;
    }
    structure_changed();
}

void World::destroy(RigidBodyId id) {
    const std::size_t b = index(id);
    const std::string name = rigid_[b].name;
    for (std::size_t s = links_.size(); s-- > 0;) {
        if (spring_defs_[s].a.body == name || spring_defs_[s].b.body == name) destroy(spring_ids_.at(s));
    }
    // Islands are numbered by their bodies: every body wakes before the numbers move.
    wake_all();
    rigid_.erase(rigid_.begin() + std::ptrdiff_t(b));
    rigid_defs_.erase(rigid_defs_.begin() + std::ptrdiff_t(b));
    rigid_built_.erase(rigid_built_.begin() + std::ptrdiff_t(b));
    shapes_.erase(shapes_.begin() + std::ptrdiff_t(b));
    rigid_contact_scratch_->cache = {};  // its pairs are by body index, which moved
    const auto first = std::ptrdiff_t(b * rigid::kStateSize), last = first + rigid::kStateSize;
    for (auto* y : {&y_, &y_tick_prev_}) y->erase(y->begin() + first, y->begin() + last);
    sleep_.rest_time.erase(sleep_.rest_time.begin() + std::ptrdiff_t(b));
    sleep_.rest_pose.erase(sleep_.rest_pose.begin() + std::ptrdiff_t(b * kRestPoseSize),
                           sleep_.rest_pose.begin() + std::ptrdiff_t((b + 1) * kRestPoseSize));
    sleep_.island.erase(sleep_.island.begin() + std::ptrdiff_t(b));
    sleep_.deepest.erase(sleep_.deepest.begin() + std::ptrdiff_t(b));
    asleep_.erase(asleep_.begin() + std::ptrdiff_t(b));
    rigid_ids_.remove(id);
    forget_body(contacts_, true, std::uint32_t(b));
    forget_body(previous_contacts_, true, std::uint32_t(b));
    if (grab_ && grab_->rigid) {
        if (grab_->body == b) grab_.reset();
        else if (grab_->body > b) --grab_->body;
    }
    structure_changed();
}

std::size_t World::index(SoftBodyId id) const {
    const std::uint32_t at = soft_ids_.index(id);
    if (at == SoftBodyId::kNone) throw InputError("that soft body no longer exists");
    return at;
}

std::size_t World::index(RigidBodyId id) const {
    const std::uint32_t at = rigid_ids_.index(id);
    if (at == RigidBodyId::kNone) throw InputError("that rigid body no longer exists");
    return at;
}

std::size_t World::index(SpringId id) const {
    const std::uint32_t at = spring_ids_.index(id);
    if (at == SpringId::kNone) throw InputError("that spring no longer exists");
    return at;
}

std::optional<SoftBodyId> World::find_soft_body(std::string_view name) const {
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        if (soft_[b].name() == name) return soft_ids_.at(b);
    }
    return std::nullopt;
}

std::optional<RigidBodyId> World::find_rigid_body(std::string_view name) const {
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (rigid_[b].name == name) return rigid_ids_.at(b);
    }
    return std::nullopt;
}

std::optional<SpringId> World::find_spring(std::string_view name) const {
    for (std::size_t s = 0; s < spring_defs_.size(); ++s) {
        if (!name.empty() && spring_defs_[s].name == name) return spring_ids_.at(s);
    }
    return std::nullopt;
}

// --- Keys -------------------------------------------------------------------------------------

void World::set_settings(const WorldSettings& settings) {
    validate(settings);
    // Switching to Verlet restarts it from the current x and v (x_{-1} = x_0 - v_0 h): its step
    // was last kept up to date when Verlet last ran, and is stale by now.
    if (settings.integrator != settings_.integrator) {
        for (SoftBody& body : soft_) body.verlet_h = 0.0f;
    }
    if (!(settings == settings_)) {
        changed_from_outside();
        wake_all();  // a key changed: whatever it does, nothing stays asleep through it
    }
    settings_ = settings;
    update_substeps();
}

void World::set_def(SoftBodyId id, const SoftBodyDef& def) {
    SoftBody& body = soft_[index(id)];
    if (def.name != body.name()) throw InputError("soft body '" + printable(body.name()) + "': its name cannot change");
    validate(def);
    check_pins(def, body.mesh);
    if (!(def == body.def)) {
        changed_from_outside();
        wake_all();
    }
    const std::shared_ptr<const Mesh> geometry = def.mesh == body.def.mesh && !def.geometry ? body.def.geometry : def.geometry;
    body.def = def;
    body.def.geometry = geometry;
    apply_body_keys(body);
    update_substeps();
}

void World::set_def(RigidBodyId id, const RigidBodyDef& def) {
    const std::size_t i = index(id);
    if (def.name != rigid_[i].name) throw InputError("rigid body '" + printable(rigid_[i].name) + "': its name cannot change");
    validate(def);
    // Refused now what the reset would refuse (a box without a size, a flat mesh).
    if (reset_keys_differ(def, rigid_built_[i], KeyOwner::RigidBody)) (void)make_rigid_body(def);
    rigid_defs_[i] = def;
    rigid_[i].restitution = def.restitution;
    rigid_[i].friction = def.friction;
    rigid_[i].color = def.color;
    wake_rigid(i);
}

void World::set_def(SpringId id, const SpringDef& def) {
    const std::size_t s = index(id);
    if (def.name != spring_defs_[s].name) throw InputError("spring '" + printable(spring_defs_[s].name) + "': its name cannot change");
    validate(def);
    Link link = resolve_link(def, def.name.empty() ? "spring" : "spring '" + printable(def.name) + "'");
    // Without a rest length of its own it keeps the one it was made with.
    if (!def.rest_length) link.l0 = links_[s].l0;
    links_[s] = link;
    spring_defs_[s] = def;
    changed_from_outside();
    wake_all();
    update_substeps();
}

ThingNames World::thing_names() const {
    ThingNames out;
    for (const SoftBody& body : soft_) out.soft.push_back(body.name());
    for (const RigidBody& body : rigid_) out.rigid.push_back(body.name);
    for (const SpringDef& spring : spring_defs_) out.springs.push_back(spring.name);
    return out;
}

void World::set_key(std::string_view name, const KeyValue& value) {
    for (const KeyTarget& t : resolve_key(name, thing_names())) {
        switch (t.owner) {
            case KeyOwner::World: {
                WorldSettings s = settings_;
                softbody::set_key(s, *t.info, value);
                set_settings(s);
                break;
            }
            case KeyOwner::SoftBody: {
                SoftBodyDef d = soft_[t.index].def;
                softbody::set_key(d, *t.info, value);
                set_def(soft_ids_.at(t.index), d);
                break;
            }
            case KeyOwner::RigidBody: {
                RigidBodyDef d = rigid_defs_[t.index];
                softbody::set_key(d, *t.info, value);
                set_def(rigid_ids_.at(t.index), d);
                break;
            }
            case KeyOwner::Spring: {
                SpringDef d = spring_defs_[t.index];
                softbody::set_key(d, *t.info, value);
                set_def(spring_ids_.at(t.index), d);
                break;
            }
        }
    }
}

void World::set_key_text(std::string_view name, std::string_view text) {
    // Parsed once, as the key the name resolves to reads it.
    const ThingNames names = thing_names();
    const std::vector<KeyTarget> targets = resolve_key(name, names);
    set_key(name, parse_key_text(targets.front(), names, text));
}

KeyValue World::key(std::string_view name) const {
    std::optional<KeyValue> out;
    for (const KeyTarget& t : resolve_key(name, thing_names())) {
        KeyValue v;
        switch (t.owner) {
            case KeyOwner::World: v = get_key(settings_, *t.info); break;
            case KeyOwner::SoftBody: v = get_key(soft_[t.index].def, *t.info); break;
            case KeyOwner::RigidBody: v = get_key(rigid_defs_[t.index], *t.info); break;
            case KeyOwner::Spring: v = get_key(spring_defs_[t.index], *t.info); break;
        }
        if (out && !(*out == v)) {
            throw InputError("key '" + printable(name) + "' differs between the soft bodies: name one (" + soft_[0].name() + "." +
                             std::string(t.info->name) + ")");
        }
        out = v;
    }
    return *out;
}

WorldDef World::def() const {
    WorldDef out;
    out.settings = settings_;
    for (const SoftBody& body : soft_) out.soft_bodies.push_back(body.def);
    out.rigid_bodies = rigid_defs_;
    out.springs = spring_defs_;
    return out;
}

bool World::reset_pending() const {
    for (const SoftBody& body : soft_) {
        if (reset_keys_differ(body.def, body.built, KeyOwner::SoftBody)) return true;
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (reset_keys_differ(rigid_defs_[b], rigid_built_[b], KeyOwner::RigidBody)) return true;
    }
    return false;
}

// --- Reset and build --------------------------------------------------------------------------

void World::reset() {
    // Bodies whose keys that apply on reset changed are made again from their definitions.
    for (SoftBody& body : soft_) {
        if (body.def.mesh != body.built.mesh) {
            body.def.geometry = std::make_shared<const Mesh>(open_mesh(body.def.mesh));
            body.mesh = *body.def.geometry;
            body.reduced.reset();
        }
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (!reset_keys_differ(rigid_defs_[b], rigid_built_[b], KeyOwner::RigidBody)) continue;
        rigid_[b] = make_rigid_body(rigid_defs_[b]);
        shapes_[b] = collision_shape(rigid_[b]);
        rigid_built_[b] = rigid_defs_[b];
    }
    build();
    // Springs without a rest length of their own measure it again, between the ends as placed.
    for (std::size_t s = 0; s < links_.size(); ++s) {
        links_[s] = resolve_link(spring_defs_[s], "spring");
    }
    update_substeps();
}

void World::build() {
    for (SoftBody& body : soft_) build_particles(body);
    soft_contacts_->build(soft_);
    soft_touching_ = false;
    y_.assign(rigid_.size() * rigid::kStateSize, 0.0);
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        std::copy(rigid_[b].initial.begin(), rigid_[b].initial.end(), y_.begin() + std::ptrdiff_t(b * rigid::kStateSize));
    }
    y_tick_prev_ = y_;
    contacts_.clear();
    previous_contacts_.clear();
    rigid_contact_scratch_->cache = {};  // a reset world starts as a new one
    reset_sleep();
    ticks_ = 0;
    status_ = Status::Ok;
    divergence_.clear();
    grab_.reset();
    changed_from_outside();
    update_substeps();
}

// A spring's ends: names to indices, each end checked, and the rest length measured where none
// is given.
Link World::resolve_link(const SpringDef& def, const std::string& what) const {
    validate(def);
    Link link;
    link.k = def.stiffness;
    link.c = def.damping;
    const auto resolve = [&](const SpringEndDef& end, const char* name) {
        const std::string where = what + ", end '" + name + "'";
        LinkEnd out;
        if (end.body.empty()) {
            if (end.vertex) throw InputError(where + ": a vertex needs a \"body\"");
            if (!end.point) throw InputError(where + ": needs a \"body\" or a \"point\" fixed in the world");
            out.kind = LinkEnd::Kind::World;
            out.point = *end.point;
            return out;
        }
        for (std::size_t b = 0; b < rigid_.size(); ++b) {
            if (rigid_[b].name != end.body) continue;
            if (end.vertex) throw InputError(where + ": rigid body '" + end.body + "' has no vertices; give a \"point\" in its axes");
            out.kind = LinkEnd::Kind::Rigid;
            out.body = std::uint32_t(b);
            out.point = end.point.value_or(Vec3d{});
            return out;
        }
        for (std::size_t b = 0; b < soft_.size(); ++b) {
            if (soft_[b].name() != end.body) continue;
            if (end.point) throw InputError(where + ": soft body '" + end.body + "' is held at a \"vertex\", not a point");
            if (!end.vertex) throw InputError(where + ": needs the \"vertex\" of soft body '" + end.body + "'");
            const auto& map = soft_[b].mesh.vertex_to_particle;
            if (*end.vertex < 0 || std::size_t(*end.vertex) >= map.size()) {
                throw InputError(where + ": vertex " + std::to_string(*end.vertex) + " does not exist (body '" + end.body + "' has " +
                                 std::to_string(map.size()) + " vertices, numbered from 0)");
            }
            out.kind = LinkEnd::Kind::Soft;
            out.body = std::uint32_t(b);
            out.particle = particle_of_vertex(soft_[b], std::uint32_t(*end.vertex));
            return out;
        }
        throw InputError(where + ": there is no body named '" + printable(end.body) + "'");
    };
    link.a = resolve(def.a, "a");
    link.b = resolve(def.b, "b");
    link.l0 = def.rest_length ? *def.rest_length : length(link_end_position(link.b) - link_end_position(link.a));
    return link;
}

Vec3d World::link_end_position(const LinkEnd& end) const {
    switch (end.kind) {
        case LinkEnd::Kind::World: return end.point;
        case LinkEnd::Kind::Rigid: {
            const RigidMotion m = rigid_motion(end.body);
            return m.x + m.R * end.point;
        }
        case LinkEnd::Kind::Soft: return Vec3d(soft_[end.body].x[end.particle]);
    }
    return {};
}

// --- Interaction ------------------------------------------------------------------------------

void World::set_threads(int threads) {
    for (SoftBody& body : soft_) body.kernel.reset();
    pool_ = std::make_unique<ThreadPool>(std::max(1, threads));
    for (SoftBody& body : soft_) body.kernel = std::make_unique<PairForceKernel>(*pool_);
}

void World::set_grab(std::optional<Grab> grab) {
    grab_ = grab;
    changed_from_outside();  // the grab does work on the body
    if (grab_ && grab_->rigid) wake_rigid(grab_->body);
}

void World::set_pinned(std::size_t b, std::uint32_t particle, bool pinned) {
    if (b >= soft_.size()) throw InputError("there is no soft body number " + std::to_string(b));
    SoftBody& body = soft_[b];
    if (particle >= body.particle_count()) return;
    // Kept as vertex numbers in the definition, so that a pin survives a reset and a saved scene.
    std::erase_if(body.def.pinned, [&](std::uint32_t v) { return particle_of_vertex(body, v) == particle; });
    if (pinned) body.def.pinned.push_back(vertex_of_particle(body, particle));
    body.built.pinned = body.def.pinned;  // in force now: nothing waits for a reset
    softbody::set_pinned(body, particle, pinned);
    changed_from_outside();
}

void World::update_substeps() {
    substeps_ = settings_.substeps;
    if (settings_.auto_substeps) {
        const int needed = stability().substeps_needed;
        substeps_ = std::max(settings_.substeps, needed > 0 ? needed : 1000);
    }
    tick_substeps_ = substeps_;
    update_contact_substeps();
}

}  // namespace softbody
