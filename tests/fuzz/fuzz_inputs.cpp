#include "fuzz_inputs.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/mesh_reduce.h"
#include "physics/keys.h"
#include "physics/scene_io.h"

namespace softbody::fuzz {

namespace {

void expect(bool ok, const std::string& what) {
    if (!ok) throw InvariantBroken(what);
}

double distance(const Vec3& a, const Vec3& b) {
    const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void check_raw(const RawMesh& raw) {
    expect(raw.triangle_corners.size() % 3 == 0, "triangle corners come in threes");
    expect(raw.triangle_corners.size() / 3 <= kMaxTriangles, "at most kMaxTriangles triangles");
    for (const Vec3& p : raw.positions) expect(is_finite(p), "every position is finite");
    for (const Vec3& n : raw.normals) expect(is_finite(n), "every normal is finite");
    for (const Corner& c : raw.triangle_corners) {
        expect(c.position >= 0 && static_cast<std::size_t>(c.position) < raw.positions.size(),
               "every corner's position index is in range");
        expect(c.normal >= -1 && (c.normal < 0 || static_cast<std::size_t>(c.normal) < raw.normals.size()),
               "every corner's normal index is in range or -1");
        expect(c.uv >= -1 && (c.uv < 0 || static_cast<std::size_t>(c.uv) < raw.uvs.size()),
               "every corner's uv index is in range or -1");
    }
}

// The OBJ file as its own check reads it (lines end at \n, \r\n or \r; tokens split at spaces
// and tabs; a token that starts with '#' ends the line; a UTF-8 byte-order mark is skipped),
// which parse_obj_text's result must match: the same vertices, and each face's triangles on
// that face's own corners (a reader that took one token for another would show here). What
// the loader forgives shows as -1: a texture-coordinate or normal index that names none defined
// so far, or names one whose numbers are not all finite (or that lacks some).
struct ObjView {
    std::size_t counts[3] = {0, 0, 0};  // v, vt, vn
    std::vector<bool> usable[3];        // per vt and vn line ([1], [2])
    std::vector<std::vector<Corner>> faces;
};

// A number the loader takes: the whole token (one leading '+' allowed), finite as a float, and
// an exponent of at most six digits after its leading zeros (the OBJ reader's own parser
// overflows on longer ones, so the loader never lets it read them).
bool finite_number(std::string_view token) {
    if (token.size() >= 2 && token[0] == '+' && token[1] != '+' && token[1] != '-') token.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return false;
    if (!std::isfinite(static_cast<float>(value))) return false;
    const std::size_t e = token.find_first_of("eE");
    if (e == std::string_view::npos) return true;
    std::string_view exponent = token.substr(e + 1);
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.remove_prefix(1);
    while (!exponent.empty() && exponent[0] == '0') exponent.remove_prefix(1);
    return exponent.size() <= 6;
}

ObjView view_obj(std::string_view text) {
    ObjView view;
    std::size_t pos = text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
    while (pos < text.size()) {
        std::size_t end = pos;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        const std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (end < text.size() && text[end] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
        std::vector<std::string_view> tokens;
        for (std::size_t i = 0; i < line.size();) {
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
            if (i < line.size() && line[i] == '#') break;
            const std::size_t start = i;
            while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
            if (i > start) tokens.push_back(line.substr(start, i - start));
        }
        if (tokens.empty()) continue;
        if (tokens[0] == "v") ++view.counts[0];
        for (const int kind : {1, 2}) {
            if (tokens[0] != (kind == 1 ? "vt" : "vn")) continue;
            ++view.counts[kind];
            bool usable = tokens.size() >= (kind == 1 ? 2u : 4u);
            for (std::size_t t = 1; t < tokens.size(); ++t) usable = usable && finite_number(tokens[t]);
            view.usable[kind].push_back(usable);
        }
        if (tokens[0] != "f") continue;
        std::vector<Corner> face;
        for (std::size_t t = 1; t < tokens.size(); ++t) {
            std::int32_t index[3] = {-1, -1, -1};
            std::string_view rest = tokens[t];
            for (int part = 0; part < 3 && !rest.empty(); ++part) {
                const std::size_t slash = std::min(rest.find('/'), rest.size());
                const std::string_view number = rest.substr(0, slash);
                rest = slash < rest.size() ? rest.substr(slash + 1) : std::string_view{};
                if (number.empty()) continue;
                // The check accepted it: a whole number; a vertex's is in range, another's may not be.
                long long i = 0;
                const std::string_view digits = number[0] == '+' ? number.substr(1) : number;
                const auto ec = std::from_chars(digits.data(), digits.data() + digits.size(), i).ec;
                const long long n = static_cast<long long>(view.counts[part]);
                if (ec != std::errc() || i == 0 || i > n || i < -n) continue;
                const long long resolved = i > 0 ? i - 1 : n + i;
                if (part > 0 && !view.usable[part][static_cast<std::size_t>(resolved)]) continue;
                index[part] = static_cast<std::int32_t>(resolved);
            }
            face.push_back({index[0], index[2], index[1]});
        }
        view.faces.push_back(std::move(face));
    }
    return view;
}

void check_obj_view(std::string_view text, const RawMesh& raw) {
    const ObjView view = view_obj(text);
    expect(raw.positions.size() == view.counts[0], "the OBJ reader sees the same vertices as the check");
    expect(raw.uvs.size() == view.counts[1], "the OBJ reader sees the same texture coordinates as the check");
    expect(raw.normals.size() == view.counts[2], "the OBJ reader sees the same normals as the check");
    std::size_t next = 0;
    for (const auto& face : view.faces) {
        const std::size_t corners = 3 * (face.size() - 2);
        expect(next + corners <= raw.triangle_corners.size(), "every face's triangles are there");
        for (std::size_t c = 0; c < corners; ++c) {
            const Corner& corner = raw.triangle_corners[next + c];
            expect(std::find(face.begin(), face.end(), corner) != face.end(),
                   "a face's triangles use that face's own corners");
            if (face.size() == 3) expect(corner == face[c], "a triangle keeps its corners in order");
        }
        next += corners;
    }
    expect(next == raw.triangle_corners.size(), "no triangle comes from nowhere");
}

// What mesh.h promises of build_mesh: one particle per distinct position (within 1e-6 of the
// bounding-box diagonal), in first-seen order; triangles on three distinct particles.
void check_mesh(const RawMesh& raw, const Mesh& mesh) {
    const std::size_t n = mesh.particle_count();
    expect(n >= 1 && n <= kMaxMeshParticles, "1 to kMaxMeshParticles particles");
    expect(mesh.vertex_to_particle.size() == raw.positions.size(), "a particle for every file vertex");

    Vec3 lo = raw.positions[0], hi = raw.positions[0];
    for (const Vec3& p : raw.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double diagonal = distance(hi, lo);
    const double eps = diagonal > 0.0 ? 1e-6 * diagonal : 1.0;
    std::size_t next = 0;  // particles are numbered in the order their first vertex appears
    for (std::size_t v = 0; v < raw.positions.size(); ++v) {
        const std::uint32_t p = mesh.vertex_to_particle[v];
        expect(p < n, "vertex_to_particle is in range");
        expect(p <= next, "particles are numbered in first-seen order");
        if (p == next) ++next;
        expect(distance(mesh.positions[p], raw.positions[v]) <= eps,
               "a vertex welds only to a particle within 1e-6 of the diagonal");
    }
    expect(next == n, "every particle has a vertex");
    if (n <= 400) {
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = i + 1; j < n; ++j) {
                expect(distance(mesh.positions[i], mesh.positions[j]) > eps,
                       "coincident vertices never become two particles");
            }
        }
    }

    expect(mesh.triangles.size() % 3 == 0, "triangles come in threes");
    expect(mesh.triangle_count() <= raw.triangle_corners.size() / 3, "welding never adds triangles");
    for (const RenderVertex& r : mesh.render_vertices) {
        expect(r.particle < n, "a render vertex's particle is in range");
        expect(r.normal_slot < mesh.normal_slot_count, "a render vertex's normal slot is in range");
        expect(std::isfinite(r.uv[0]) && std::isfinite(r.uv[1]), "texture coordinates are finite");
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        std::uint32_t particle[3];
        for (std::size_t c = 0; c < 3; ++c) {
            const std::uint32_t r = mesh.triangles[t + c];
            expect(r < mesh.render_vertices.size(), "a triangle's render vertex is in range");
            particle[c] = mesh.render_vertices[r].particle;
        }
        expect(particle[0] != particle[1] && particle[1] != particle[2] && particle[0] != particle[2],
               "a triangle spans three distinct particles");
    }
}

// What mesh_reduce.h promises of reduce_mesh, for a budget of about half the particles: at most
// the budget, a subset of the positions with maps both ways, kept particles bound to
// themselves, every binding's particles in range and its numbers finite.
void check_reduced(const Mesh& mesh) {
    const std::size_t n = mesh.particle_count();
    const std::size_t budget = std::max(kMinReducedParticles, n / 2);
    const ReducedMesh reduced = reduce_mesh(mesh, budget);
    expect(reduced.particle_count() <= budget, "at most the budget");
    expect(reduced.particle_count() >= std::min(n, kMinReducedParticles), "at least a tetrahedron's worth");
    expect(reduced.reduced_to_full.size() == reduced.particle_count() && reduced.full_to_reduced.size() == n &&
               reduced.bindings.size() == n,
           "one map entry and one binding per particle");
    for (std::uint32_t r = 0; r < reduced.particle_count(); ++r) {
        const std::uint32_t f = reduced.reduced_to_full[r];
        expect(f < n && reduced.full_to_reduced[f] == r, "the maps agree");
        expect(reduced.positions[r] == mesh.positions[f], "a simulated particle is a full one");
        expect(reduced.bindings[f] == SkinBinding{{r, r, r}, {1.0f, 0.0f, 0.0f}, 0.0f}, "a kept particle binds to itself");
    }
    for (const SkinBinding& b : reduced.bindings) {
        for (std::uint32_t p : b.particles) expect(p < reduced.particle_count(), "a binding's particles are in range");
        for (float w : b.weights) expect(std::isfinite(w), "a binding's weights are finite");
        expect(std::isfinite(b.offset), "a binding's offset is finite");
    }
    for (std::uint32_t p : reduced.triangles) expect(p < reduced.particle_count(), "a reduced triangle is in range");
}

// Saves the scene as a scene file's text and reads it back.
void expect_scene_round_trip(const Scene& scene) {
    std::string saved;
    try {
        saved = scene_to_json(scene);
    } catch (const InputError&) {
        return;  // a mesh path that is not UTF-8: refused by name, nothing written
    }
    Scene back;
    try {
        back = parse_scene(saved, "fuzz.json");
    } catch (const InputError& e) {
        throw InvariantBroken(std::string("a saved scene loads back: ") + e.what());
    }
    expect(back == scene, "a saved scene loads back the same scene");
}

}  // namespace

void mesh_input(std::string_view data) {
    const std::string text(data);
    for (const bool off : {false, true}) {
        RawMesh raw;
        try {
            raw = off ? parse_off_text(text, "fuzz.off") : parse_obj_text(text, "fuzz.obj");
        } catch (const InputError&) {
            continue;
        }
        check_raw(raw);
        if (!off) check_obj_view(text, raw);
        Mesh mesh;
        try {
            mesh = build_mesh(raw, "fuzz");
        } catch (const InputError&) {
            continue;
        }
        check_mesh(raw, mesh);
        check_reduced(mesh);  // an InputError here is a broken promise: the budget is valid
    }
}

void scene_input(std::string_view data) {
    Scene scene;
    try {
        scene = parse_scene(std::string(data), "fuzz.json");
    } catch (const InputError&) {
        return;
    }
    try {
        validate(scene.settings);
        for (const SoftBodyDef& body : scene.soft_bodies) validate(body);
        for (const RigidBodyDef& body : scene.rigid_bodies) validate(body);
        for (const SpringDef& spring : scene.springs) validate(spring);
    } catch (const InputError& e) {
        throw InvariantBroken(std::string("a scene that loads is valid: ") + e.what());
    }
    expect_scene_round_trip(scene);
}

// A scene with one of each thing, named as `--set` names them: the soft body "body", the rigid
// body "crate", the spring "coil".
Scene set_base() {
    Scene scene;
    SoftBodyDef body;
    body.name = "body";
    body.mesh = "cube:2";
    scene.soft_bodies.push_back(body);
    RigidBodyDef crate;
    crate.name = "crate";
    crate.size = Vec3d{1.0, 1.0, 1.0};
    scene.rigid_bodies.push_back(crate);
    SpringDef coil;
    coil.name = "coil";
    coil.a.point = Vec3d{0.0, 0.0, 3.0};
    coil.b.body = "crate";
    coil.stiffness = 10.0;
    scene.springs.push_back(coil);
    return scene;
}

void set_input(std::string_view data) {
    Scene scene = set_base();
    for (std::size_t start = 0; start <= data.size();) {
        const std::size_t end = std::min(data.find('\n', start), data.size());
        const std::string_view line = data.substr(start, end - start);
        start = end + 1;
        const std::size_t eq = line.find('=');
        const std::string_view key = line.substr(0, eq);
        const std::string_view value = eq == std::string_view::npos ? std::string_view{} : line.substr(eq + 1);

        const Scene before = scene;
        try {
            set_scene_key(scene, key, value);
        } catch (const InputError&) {
            expect(scene == before, "a refused --set changes nothing");
            continue;
        }
        try {
            validate(scene.settings);
            for (const SoftBodyDef& body : scene.soft_bodies) validate(body);
            for (const RigidBodyDef& body : scene.rigid_bodies) validate(body);
            for (const SpringDef& spring : scene.springs) validate(spring);
        } catch (const InputError& e) {
            throw InvariantBroken(std::string("an accepted --set leaves valid keys: ") + e.what());
        }
        const std::vector<KeyTarget> targets = resolve_key(key, thing_names(scene));
        if (targets.front().info->alias) continue;  // write-only: it set another key
        const std::string text = key_text(*targets.front().info, get_key(scene, targets.front()));
        Scene again = scene;
        try {
            set_scene_key(again, key, text);
        } catch (const InputError& e) {
            throw InvariantBroken(std::string("key_text gives text that --set accepts: ") + e.what());
        }
        expect(again == scene, "--set of a key's own text gives back the same value");
    }
    expect_scene_round_trip(scene);
}

}  // namespace softbody::fuzz
