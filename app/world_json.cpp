#include "world_json.h"

namespace softbody::app {

nlohmann::ordered_json vec_json(const Vec3d& v) { return {v.x, v.y, v.z}; }

nlohmann::ordered_json rigid_body_json(const World& world, std::size_t b) {
    const RigidBody& body = world.rigid_body(b);
    const RigidMotion m = world.rigid_motion(b);
    const Mat3 J = m.R * body.J_body * m.R.transposed();  // Eq. 32, world axes
    nlohmann::ordered_json inertia = nlohmann::ordered_json::array();
    for (int i = 0; i < 3; ++i) inertia.push_back({J.m[i][0], J.m[i][1], J.m[i][2]});
    const double kinetic = body.fixed ? 0.0 : 0.5 * dot(m.P, m.v) + 0.5 * dot(m.L, m.omega);
    return {{"name", body.name},
            {"shape", std::string(to_string(body.shape))},
            {"mass", body.mass},
            {"fixed", body.fixed},
            {"position", vec_json(m.x)},
            {"orientation", {m.q.w, m.q.x, m.q.y, m.q.z}},
            {"velocity", vec_json(m.v)},
            {"angular_velocity", vec_json(m.omega)},
            {"angular_momentum", vec_json(m.L)},
            {"inertia", inertia},
            {"kinetic_energy", kinetic},
            {"asleep", world.rigid_asleep(b)}};
}

nlohmann::ordered_json rigid_bodies_json(const World& world) {
    nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) bodies.push_back(rigid_body_json(world, b));
    return bodies;
}

nlohmann::ordered_json soft_bodies_json(const World& world) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const SoftBody& body = world.soft_body(b);
        out.push_back({{"name", body.name()},
                       {"mesh", body.mesh.source},
                       {"vertices", body.mesh.vertex_to_particle.size()},
                       {"mesh_particles", body.mesh.particle_count()},
                       {"particles", body.particle_count()},
                       {"scale", body.scale_used},
                       {"scale_auto", body.def.scale == 0.0f},
                       {"up_axis", body.def.up_axis}});
    }
    return out;
}

}  // namespace softbody::app
