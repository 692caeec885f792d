// softbody bench: the physics alone, timed, on the scenes the app opens: generated point
// clouds (cloud:N, physics/generated.h), the bundled meshes through their scene files, and a
// pile of rigid bodies with and without a cloud on it.
//
// First it measures this CPU's peak (PairForceKernel::peak_flops: multiply-add chains at each
// vector width the pair kernel has a tile for, on 1 thread and on all). For each size it times
// whole ticks (World::tick, dt = 0.02 s, the substeps stability needs) with the fast pair kernel
// at 1 and at all threads, with the readable reference kernel, and with "the baseline": a
// straightforward transcription of Listing 8 written below, kept here only to measure against.
// It times the pair kernel alone for every tile variant and gives each its fraction of the
// peak, then searches the largest cloud that still runs in real time. The frame side (streaming
// positions and normals) is `softbody render --bench`'s, which times the renderer's own code.
// Then "rigid bodies at scale": piles of boxes and balls and pyramids of boxes timed over whole
// runs, beside the same scenes in Bullet when its peer, softbody_peer_bullet, was built. Last,
// "busy machine": the same kinds of scenes at 1 and at all threads while another process spins on
// one core, and how much the second thread costs or saves there.
//
// Every measurement runs in a child process of its own, so each row's peak memory
// (getrusage's ru_maxrss) is that row's alone.
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "busy_core.h"
#include "cli.h"
#include "commands.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/mesh.h"
#include "physics/pair_forces.h"
#include "physics/scene_io.h"
#include "physics/world.h"
#include "soundness.h"

extern char** environ;

namespace softbody::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// =============================================================================================
// The baseline: Listing 8 transcribed the straightforward way, for this benchmark only.
// A 3-vector struct per particle, N x N tables of k, c and rest length, and every particle
// looping over all the others (each pair is evaluated twice, once from each end). Students
// should read pair_forces_reference instead; this is what the fast kernel is measured against.
// =============================================================================================
namespace baseline {

struct Vector {
    float x, y, z;
    Vector operator+(const Vector& o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vector operator-(const Vector& o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vector operator*(float s) const { return {x * s, y * s, z * s}; }
    Vector operator/(float s) const { return {x / s, y / s, z / s}; }
    float Magnitude() const { return std::sqrt(x * x + y * y + z * z); }
};
float Dot(const Vector& a, const Vector& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct Particle {
    Vector vPosition, vPreviousPosition, vVelocity, vForces;
    float fMass;
};

class SoftBody {
public:
    SoftBody(const std::vector<Vec3>& positions, float k, float c, float mass) : n_(positions.size()) {
        particles_.resize(n_);
        for (std::size_t i = 0; i < n_; ++i) {
            const Vector p{positions[i].x, positions[i].y, positions[i].z};
            particles_[i] = {p, p, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, mass};
        }
        springK_.assign(n_ * n_, k);
        damperC_.assign(n_ * n_, c);
        restLength_.resize(n_ * n_);
        for (std::size_t i = 0; i < n_; ++i) {
            for (std::size_t j = 0; j < n_; ++j) {
                restLength_[i * n_ + j] = (particles_[j].vPosition - particles_[i].vPosition).Magnitude();
            }
        }
    }

    // Listing 8's CalcForce: gravity, then a spring and a damper to every other particle.
    void CalcForces() {
        for (std::size_t i = 0; i < n_; ++i) {
            Particle& pi = particles_[i];
            pi.vForces = Vector{0.0f, 0.0f, -9.81f} * pi.fMass;
            for (std::size_t j = 0; j < n_; ++j) {
                if (j == i) continue;
                const Particle& pj = particles_[j];
                const Vector d = pj.vPosition - pi.vPosition;
                const float l = d.Magnitude();
                if (l == 0.0f) continue;
                const Vector dHat = d / l;
                const Vector fSpring = dHat * (springK_[i * n_ + j] * (l - restLength_[i * n_ + j]));
                const Vector fDamper = dHat * (damperC_[i * n_ + j] * Dot(pj.vVelocity - pi.vVelocity, dHat));
                pi.vForces = pi.vForces + fSpring + fDamper;
            }
        }
    }

    // Position Verlet with Euler velocities, as the project's default integrator.
    void StepSimulation(float h) {
        CalcForces();
        for (Particle& p : particles_) {
            const Vector a = p.vForces / p.fMass;
            const Vector x = p.vPosition;
            p.vPosition = x * 2.0f - p.vPreviousPosition + a * (h * h);
            p.vPreviousPosition = x;
            p.vVelocity = p.vVelocity + a * h;
        }
    }

    bool finite() const {
        for (const Particle& p : particles_) {
            if (!std::isfinite(p.vPosition.x + p.vPosition.y + p.vPosition.z)) return false;
        }
        return true;
    }

private:
    std::size_t n_;
    std::vector<Particle> particles_;
    std::vector<float> springK_, damperC_, restLength_;
};

}  // namespace baseline

// =============================================================================================
// Measurements
// =============================================================================================

// One row of the table. Plain data: it crosses a pipe from the child process that measured it.
struct Measurement {
    int measured = 0;       // 0: it failed, see note
    int diverged = 0;
    int threads = 1;
    int substeps = 1;
    int ticks = 0;          // ticks timed
    double median_s = 0.0;  // per tick
    double best_s = 0.0;
    double pairs_per_tick = 0.0;  // unique pairs, substeps * N(N-1)/2
    double evals_per_tick = 0.0;  // pair evaluations actually made (the baseline makes each twice)
    double h_omega = 0.0;         // stability estimate at the substeps in use
    double limit = 2.0;
    long peak_kb = 0;
    char note[240] = {};
};

// Runs `measure` in a child process and returns what it measured, with the child's peak RSS.
// T is plain data with `measured`, `note` and `peak_kb` (Measurement, ScaleRun).
// A browser page cannot fork: there it measures in the page's process, and the peak is not known.
template <class T>
T in_child(const std::function<T()>& measure) {
#if defined(__EMSCRIPTEN__)
    T m;
    try {
        m = measure();
    } catch (const std::exception& e) {
        m.measured = 0;
        std::snprintf(m.note, sizeof m.note, "%s", e.what());
    }
    return m;
#else
    int fd[2];
    if (pipe(fd) != 0) throw std::runtime_error("bench: pipe failed");
    std::cout.flush();
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("bench: fork failed");
    if (pid == 0) {
        close(fd[0]);
        T m;
        try {
            m = measure();
        } catch (const std::exception& e) {
            m.measured = 0;
            std::snprintf(m.note, sizeof m.note, "%s", e.what());
        }
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        m.peak_kb = usage.ru_maxrss;
        const char* bytes = reinterpret_cast<const char*>(&m);
        std::size_t sent = 0;
        while (sent < sizeof m) {
            const ssize_t w = write(fd[1], bytes + sent, sizeof m - sent);
            if (w <= 0) break;
            sent += static_cast<std::size_t>(w);
        }
        _exit(0);
    }
    close(fd[1]);
    T m;
    char* bytes = reinterpret_cast<char*>(&m);
    std::size_t got = 0;
    for (;;) {
        const ssize_t r = read(fd[0], bytes + got, sizeof m - got);
        if (r > 0) got += static_cast<std::size_t>(r);
        else if (r < 0 && errno == EINTR) continue;
        else break;
        if (got == sizeof m) break;
    }
    close(fd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (got != sizeof m) {
        m = T{};
        std::snprintf(m.note, sizeof m.note, "the measuring process died (%s)",
                      WIFSIGNALED(status) ? strsignal(WTERMSIG(status)) : "no result");
    }
    return m;
#endif
}

// Times tick() one call at a time until `budget` seconds have passed (at least min_ticks,
// at most max_ticks, and only while ok()). With warm_up, one untimed tick first.
void time_ticks(Measurement& m, const std::function<void()>& tick, const std::function<bool()>& ok, double budget,
                int min_ticks, int max_ticks, bool warm_up) {
    if (warm_up && ok()) tick();
    std::vector<double> times;
    const auto start = Clock::now();
    while (ok() && int(times.size()) < max_ticks && (int(times.size()) < min_ticks || seconds_since(start) < budget)) {
        const auto t0 = Clock::now();
        tick();
        times.push_back(seconds_since(t0));
    }
    m.ticks = int(times.size());
    if (times.empty()) return;
    std::sort(times.begin(), times.end());
    m.best_s = times.front();
    m.median_s = times.size() % 2 ? times[times.size() / 2] : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
    m.measured = 1;
}

enum class Kernel { Fast, Reference, Baseline };

// One tick-timing row of a scene (a file, or a generated name such as cloud:2500 or pile:100):
// the World with the fast or the reference kernel, or the baseline on the scene's soft body, in
// a child. `settle` ticks run first, untimed (a pile's second of fall: the contacts busy).
Measurement measure_scene(Kernel kernel, const std::function<Scene()>& make, int threads, double budget, int settle = 0) {
    return in_child<Measurement>([&]() {
        Measurement m;
        const Scene scene = make();
        World world(scene, WorldOptions{threads, kernel == Kernel::Reference});
        const double n = double(world.soft_body_count() ? world.soft_body(0).particle_count() : 0);
        m.substeps = world.substeps_in_use();
        if (n > 0) {
            const Stability s = world.stability();
            m.h_omega = s.h_omega;
            m.limit = s.limit;
        }
        if (kernel == Kernel::Baseline) {
            // The scene's soft body where the World starts it, at the substeps the World picked,
            // so the rows compare like with like.
            const SoftBodyDef& keys = scene.soft_bodies.front();
            const Vec3Array& x = world.soft_body(0).x;
            std::vector<Vec3> positions(x.size());
            for (std::size_t i = 0; i < x.size(); ++i) positions[i] = x[i];
            baseline::SoftBody body(positions, keys.stiffness, keys.damping, keys.particle_mass);
            const float h = scene.settings.dt / float(m.substeps);
            const int substeps = m.substeps;
            time_ticks(
                m, [&] { for (int step = 0; step < substeps; ++step) body.StepSimulation(h); }, [&] { return body.finite(); },
                budget, 1, 1000, false);
            m.threads = 1;
            m.pairs_per_tick = m.substeps * n * (n - 1.0) / 2.0;
            m.evals_per_tick = m.substeps * n * (n - 1.0);
            if (!body.finite()) m.diverged = 1;
            return m;
        }
        m.threads = world.threads();
        if (settle > 0) world.run(settle);
        time_ticks(
            m, [&] { world.tick(); }, [&] { return world.status() == Status::Ok; }, budget, kernel == Kernel::Fast ? 3 : 1,
            20000, kernel == Kernel::Fast && settle == 0);
        // Every soft body's pairs (a scene of several: each its own N(N-1)/2).
        double pairs = 0.0;
        for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
            const double nb = double(world.soft_body(b).particle_count());
            pairs += nb * (nb - 1.0) / 2.0;
        }
        m.pairs_per_tick = m.substeps * pairs;
        m.evals_per_tick = m.pairs_per_tick;
        if (world.status() != Status::Ok) {
            m.diverged = 1;
            std::snprintf(m.note, sizeof m.note, "%s", world.divergence().c_str());
        }
        return m;
    });
}

Measurement measure(Kernel kernel, const std::string& scene_name, int threads, double budget, int settle = 0) {
    return measure_scene(kernel, [&] { return load_scene(scene_name); }, threads, budget, settle);
}

std::string cloud(std::size_t n) { return "cloud:" + std::to_string(n); }

// Two soft cubes of cube:22 (2,906 particles each, 0.6 m a side) on the ground: one resting on
// the other (a whole face in contact: the most pairs a tick finds), or side by side, apart
// (the broad phase finds nothing after the bodies' boxes). What soft contacts cost per tick is
// the difference.
Scene two_cubes(bool touching) {
    Scene scene;
    for (int k = 0; k < 2; ++k) {
        SoftBodyDef body;
        body.name = k == 0 ? "lower" : "upper";
        body.mesh = "cube:22";
        body.scale = 0.6f;
        body.max_particles = 0;
        body.stiffness = 2.0f;  // soft enough to sag onto the lower cube; few substeps (7)
        body.damping = 0.005f;
        body.particle_mass = 0.05f;
        body.position = touching ? Vec3{0.0f, 0.0f, 0.3f + 0.61f * float(k)} : Vec3{-0.5f + 1.0f * float(k), 0.0f, 0.3f};
        scene.soft_bodies.push_back(body);
    }
    return scene;
}

// A soft ball (ball:2: 162 particles, 0.7 m across, k 120) dropped 1.5 m onto pyramid:3 (14
// boxes), and each of the two alone (the ball on the ground): what a soft body resting on rigid
// bodies costs against the two apart, timed after 2 s (landed, at rest).
Scene ball_on_pyramid(bool ball, bool pyramid) {
    Scene scene = pyramid ? load_scene("pyramid:3") : Scene{};
    if (ball) {
        SoftBodyDef body;
        body.name = "ball";
        body.mesh = "ball:2";
        body.scale = 0.7f;
        body.particle_mass = 0.05f;
        body.stiffness = 120.0f;
        body.damping = 0.5f;
        body.position = Vec3{0.0f, 0.0f, (pyramid ? 3.0f : 0.0f) + 1.5f + 0.35f};
        scene.soft_bodies.push_back(body);
    }
    return scene;
}

// The pair kernel alone, one tile variant: compute() on a cloud displaced from rest and moving,
// no tick around it. calls/ticks are force evaluations here.
Measurement measure_kernel(PairKernelVariant variant, std::size_t n, int threads, double budget) {
    return in_child<Measurement>([&]() {
        Measurement m;
        const Mesh mesh = generated_mesh(cloud(n));
        std::mt19937 rng(7u);
        std::uniform_real_distribution<float> u(-0.05f, 0.05f);
        Vec3Array x, v, r;
        x.resize(n);
        v.resize(n);
        r.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            r.set(i, mesh.positions[i]);
            x.set(i, mesh.positions[i] + Vec3{u(rng), u(rng), u(rng)});
            v.set(i, Vec3{u(rng), u(rng), u(rng)} * 20.0f);
        }
        const PairInput in{x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data(),
                           r.x.data(), r.y.data(), r.z.data(), n, 10.0f, 0.1f};
        ThreadPool pool(threads);
        PairForceKernel kernel(pool, variant);
        Vec3Array f;
        time_ticks(m, [&] { kernel.compute(in, f); }, [] { return true; }, budget, 3, 100000, true);
        m.threads = threads;
        m.pairs_per_tick = double(n) * double(n - 1) / 2.0;
        m.evals_per_tick = m.pairs_per_tick;
        return m;
    });
}

struct Row {
    std::string scene;  // "cloud", the mesh file's name, or a generated scene's ("pile:100")
    std::size_t n = 0;
    std::string kernel;  // "fast (avx512)", "reference", "baseline"
    Measurement m;
};

double ms(double seconds) { return seconds * 1e3; }

std::string si(double value) {
    char text[32];
    if (!(value > 0.0)) return "-";  // no pairs: a scene of rigid bodies only
    if (value >= 1e9) std::snprintf(text, sizeof text, "%.2fe9", value / 1e9);
    else if (value >= 1e6) std::snprintf(text, sizeof text, "%.1fe6", value / 1e6);
    else std::snprintf(text, sizeof text, "%.0f", value);
    return text;
}

nlohmann::ordered_json row_json(const Row& r, double dt) {
    const Measurement& m = r.m;
    nlohmann::ordered_json j = {{"scene", r.scene}, {"particles", r.n}, {"kernel", r.kernel}, {"threads", m.threads},
                                {"substeps", m.substeps}, {"ticks_measured", m.ticks}};
    if (m.measured) {
        j["ms_per_tick_median"] = ms(m.median_s);
        j["ms_per_tick_best"] = ms(m.best_s);
        j["pairs_per_second"] = m.pairs_per_tick / m.median_s;
        j["pair_evaluations_per_second"] = m.evals_per_tick / m.median_s;
        j["ticks_per_second"] = 1.0 / m.median_s;
        j["real_time_factor"] = dt / m.median_s;
    }
    j["stability_h_omega"] = m.h_omega;
    j["stability_limit"] = m.limit;
    j["peak_memory_mb"] = double(m.peak_kb) * 1024.0 / 1e6;
    j["status"] = !m.measured ? "failed" : m.diverged ? "diverged" : "ok";
    if (m.note[0]) j["note"] = m.note;
    return j;
}

void print_header(std::ostream& out) {
    char line[256];
    std::snprintf(line, sizeof line, "%-20s %6s  %-15s %3s %4s %6s %17s %9s %9s %8s %8s %8s", "scene", "N", "kernel",
                  "thr", "sub", "ticks", "ms/tick (best)", "pairs/s", "evals/s", "ticks/s", "x realtm", "peak MB");
    out << line << "\n";
}

void print_row(std::ostream& out, const Row& r, double dt) {
    const Measurement& m = r.m;
    char line[512];
    if (!m.measured) {
        std::snprintf(line, sizeof line, "%-20s %6zu  %-15s %3d %4d  failed: %s", r.scene.c_str(), r.n, r.kernel.c_str(),
                      m.threads, m.substeps, m.note);
    } else {
        char timing[40];
        std::snprintf(timing, sizeof timing, "%.4g (%.4g)", ms(m.median_s), ms(m.best_s));
        std::snprintf(line, sizeof line, "%-20s %6zu  %-15s %3d %4d %6d %17s %9s %9s %8.1f %8.2f %8.0f%s", r.scene.c_str(),
                      r.n, r.kernel.c_str(), m.threads, m.substeps, m.ticks, timing, si(m.pairs_per_tick / m.median_s).c_str(),
                      si(m.evals_per_tick / m.median_s).c_str(), 1.0 / m.median_s, dt / m.median_s, double(m.peak_kb) * 1024.0 / 1e6,
                      m.diverged ? "  DIVERGED" : "");
    }
    out << line << "\n";
}

std::vector<std::size_t> parse_sizes(std::string_view text) {
    std::vector<std::size_t> sizes;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        sizes.push_back(static_cast<std::size_t>(
            parse_int("--sizes", text.substr(start, comma - start), 2, static_cast<std::int64_t>(kMaxParticles))));
        start = comma + 1;
    }
    return sizes;
}

// The bundled scene files that show a mesh on its own: a soft body and no rigid bodies
// (cow.json, knot.json, ...), as the app opens them.
std::vector<std::string> bundled_mesh_scenes() {
    std::vector<std::string> files;
    const std::filesystem::path folder = std::filesystem::path(assets_dir()) / "scenes";
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
        if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// This CPU's peak at one variant's width, on `threads` threads.
struct Peak {
    PairKernelVariant variant;
    int threads = 1;
    double flops = 0.0;  // per second
};

const char* width_of(PairKernelVariant variant) {
    switch (variant) {
        case PairKernelVariant::Avx512: return "512-bit";
        case PairKernelVariant::Avx2: return "256-bit";
        case PairKernelVariant::WasmSimd128: return "128-bit";
        default: return "scalar";
    }
}

// =============================================================================================
// Rigid bodies at scale: the five scenes, softbody against its peer
// =============================================================================================
// Each run simulates a whole stretch (10 s, 3 s for the 20-layer pyramid) and gives ms per
// tick over all of it, the wall clock of the ticks alone (not a median after settling: falling,
// piling up and resting all count), then the soundness figures of app/soundness.h. softbody
// runs in a child process as the rows above; the peer (softbody_peer_bullet, built where Bullet
// is installed) is its own executable beside this one.

// The bench's own scenes, then the same kinds built as another engine's comparison built them
// (bin:N, stack:L: generated.h), which the solver was not tuned on; each pyramid also with
// sleeping off (NAME@KEY=VALUE: the scene with that key set, as `simulate --set` sets it).
const std::vector<std::string> kScaleScenes{"boxes:100",
                                            "boxes:1000",
                                            "boxes:3000",
                                            "pyramid:10",
                                            "pyramid:10@sleeping=false",
                                            "pyramid:20",
                                            "pyramid:20@sleeping=false",
                                            "bin:1000",
                                            "bin:3000",
                                            "stack:10",
                                            "stack:10@sleeping=false",
                                            "stack:20",
                                            "stack:20@sleeping=false"};

// A scene of the section: its name, then any KEY=VALUE after an '@' each.
struct ScaleScene {
    std::string name;
    std::vector<std::pair<std::string, std::string>> keys;
};

ScaleScene parse_scale_scene(const std::string& spec) {
    ScaleScene scene;
    std::size_t at = spec.find('@');
    scene.name = spec.substr(0, at);
    while (at != std::string::npos) {
        const std::size_t next = spec.find('@', at + 1);
        const std::string assignment = spec.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
        const std::size_t eq = assignment.find('=');
        if (eq == std::string::npos || eq == 0) {
            throw UsageError("--scale-scenes: expected NAME@KEY=VALUE, got '" + spec + "'");
        }
        scene.keys.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
        at = next;
    }
    return scene;
}

Scene load_scale_scene(const std::string& spec) {
    const ScaleScene parsed = parse_scale_scene(spec);
    Scene scene = load_scene(parsed.name);
    for (const auto& [key, value] : parsed.keys) set_scene_key(scene, key, value);
    return scene;
}

// Simulated seconds of a scene's run: 10, and 3 for pyramids of 20 layers or more (softbody's
// 20-layer pyramid takes most of a second a tick today).
double default_scale_seconds(const std::string& spec) {
    const std::string scene = parse_scale_scene(spec).name;
    if (is_pyramid(scene)) {
        const std::string layers = scene.substr(scene.find(':') + 1);
        if (!layers.empty() && layers.find_first_not_of("0123456789") == std::string::npos && std::stoi(layers) >= 20) return 3.0;
    }
    return 10.0;
}

// One softbody run. Plain data: it crosses a pipe from the child process that measured it.
struct ScaleRun {
    int measured = 0;
    int diverged = 0;
    int threads = 1;
    int ticks = 0;
    int bodies = 0;
    double seconds = 0.0;
    double ms_per_tick = 0.0;
    int has_ground = 0;
    double penetration_m = 0.0;
    int moving = 0;
    int sleeping = 0;
    double kinetic_J = 0.0;
    int has_top = 0;
    double top_moved_m = 0.0;
    long peak_kb = 0;
    char note[240] = {};
};

ScaleRun measure_scale(const std::string& scene_name, int threads, double seconds) {
    return in_child<ScaleRun>([&]() {
        ScaleRun r;
        const Scene scene = load_scale_scene(scene_name);
        World world(scene, WorldOptions{threads, false});
        r.threads = world.threads();
        r.ticks = std::max(1, int(std::lround(seconds / double(world.settings().dt))));
        Clock::duration spent{};
        int done = 0;
        for (; done < r.ticks && world.status() == Status::Ok; ++done) {
            const auto t0 = Clock::now();
            world.tick();
            spent += Clock::now() - t0;
        }
        r.ms_per_tick = std::chrono::duration<double, std::milli>(spent).count() / std::max(1, done);
        r.seconds = std::round(double(done) * double(world.settings().dt) * 1e6) / 1e6;  // 0.2, not float's 0.19999999
        if (world.status() != Status::Ok) {
            r.diverged = 1;
            std::snprintf(r.note, sizeof r.note, "%s", world.divergence().c_str());
        }
        std::vector<RigidBody> defs;
        std::vector<BodyNow> now;
        for (std::size_t i = 0; i < world.rigid_body_count(); ++i) {
            const RigidMotion m = world.rigid_motion(i);
            defs.push_back(world.rigid_body(i));
            now.push_back({m.x, m.R, m.v, m.omega, lowest_point(world.rigid_body(i), m.x, m.R), world.rigid_asleep(i)});
        }
        const WorldSettings& p = world.settings();
        const Soundness s = soundness(defs, now, p.ground ? std::optional<double>(p.ground_height) : std::nullopt,
                                      is_pyramid(scene_name));
        r.bodies = s.bodies;
        r.has_ground = s.penetration_m.has_value();
        r.penetration_m = s.penetration_m.value_or(0.0);
        r.moving = s.moving;
        r.sleeping = s.sleeping;
        r.kinetic_J = s.kinetic_J;
        r.has_top = s.top_moved_m.has_value();
        r.top_moved_m = s.top_moved_m.value_or(0.0);
        r.measured = 1;
        return r;
    });
}

// One row of the section, softbody's or the peer's.
struct ScaleRow {
    std::string scene, engine, config;  // engine "softbody" or "bullet"; config "1 thread", "10 iterations", ...
    std::string status = "failed", note;
    int bodies = 0, ticks = 0;
    double seconds = 0.0, ms_per_tick = 0.0;
    std::optional<double> penetration_m, top_moved_m;
    int moving = 0;
    double kinetic_J = 0.0;
    std::optional<int> threads, sleeping, steps;
    long peak_kb = 0;
};

ScaleRow softbody_row(const std::string& scene, const ScaleRun& r) {
    ScaleRow row;
    row.scene = scene;
    row.engine = "softbody";
    row.config = std::to_string(r.threads) + (r.threads > 1 ? " threads" : " thread");
    row.threads = r.threads;
    row.note = r.note;
    if (!r.measured) return row;
    row.status = r.diverged ? "diverged" : "ok";
    row.bodies = r.bodies;
    row.ticks = r.ticks;
    row.seconds = r.seconds;
    row.ms_per_tick = r.ms_per_tick;
    if (r.has_ground) row.penetration_m = r.penetration_m;
    if (r.has_top) row.top_moved_m = r.top_moved_m;
    row.moving = r.moving;
    row.sleeping = r.sleeping;
    row.kinetic_J = r.kinetic_J;
    row.peak_kb = r.peak_kb;
    return row;
}

// The machine's load average over the last minute (/proc/loadavg), or -1: the section prints it
// before and after, since other work on the machine shows in whole-run times.
double load_average() {
    std::FILE* file = std::fopen("/proc/loadavg", "r");
    if (!file) return -1.0;
    double load = -1.0;
    if (std::fscanf(file, "%lf", &load) != 1) load = -1.0;
    std::fclose(file);
    return load;
}

// The peer beside this executable, if it was built: its path, or empty.
std::string find_peer() {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return {};
    const std::filesystem::path peer = self.parent_path() / "softbody_peer_bullet";
    if (access(peer.c_str(), X_OK) != 0) return {};
    return peer.string();
}

// Runs the peer for one scene and one configuration; its stdout comes back through a pipe, its
// stderr goes to ours (a refusal says why there).
ScaleRow run_peer(const std::string& peer, const std::string& scene, const char* config, const char* label, double seconds) {
    ScaleRow row;
    row.scene = scene;
    row.engine = "bullet";
    row.config = label;
    char seconds_text[32];
    std::snprintf(seconds_text, sizeof seconds_text, "%.17g", seconds);
    std::vector<std::string> args{peer, "--scene", scene, "--config", config, "--seconds", seconds_text};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    int fd[2];
    if (pipe(fd) != 0) throw std::runtime_error("bench: pipe failed");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fd[1], 1);
    posix_spawn_file_actions_addclose(&actions, fd[0]);
    posix_spawn_file_actions_addclose(&actions, fd[1]);
    std::cout.flush();
    std::fflush(stdout);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, peer.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fd[1]);
    std::string out;
    char buffer[4096];
    for (;;) {
        const ssize_t n = read(fd[0], buffer, sizeof buffer);
        if (n > 0) out.append(buffer, std::size_t(n));
        else if (n < 0 && errno == EINTR) continue;
        else break;
    }
    close(fd[0]);
    if (spawned != 0) {
        row.note = std::string("could not start the peer: ") + std::strerror(spawned);
        return row;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        row.note = WIFSIGNALED(status) ? std::string("the peer died (") + strsignal(WTERMSIG(status)) + ")"
                                       : "the peer exited with " + std::to_string(WEXITSTATUS(status)) + " (its message is above)";
        return row;
    }
    try {
        const nlohmann::json j = nlohmann::json::parse(out);
        row.status = j.at("status").get<std::string>();
        row.bodies = j.at("bodies").get<int>();
        row.ticks = j.at("ticks").get<int>();
        row.seconds = j.at("seconds").get<double>();
        row.ms_per_tick = j.at("ms_per_tick").get<double>();
        if (!j.at("penetration_m").is_null()) row.penetration_m = j.at("penetration_m").get<double>();
        if (!j.at("top_moved_m").is_null()) row.top_moved_m = j.at("top_moved_m").get<double>();
        row.moving = j.at("moving").get<int>();
        row.kinetic_J = j.at("kinetic_J").get<double>();
        row.sleeping = j.at("sleeping").get<int>();
        row.steps = j.at("steps").get<int>();
    } catch (const std::exception& e) {
        row.status = "failed";
        row.note = std::string("the peer's output did not read as its JSON: ") + e.what();
    }
    return row;
}

nlohmann::ordered_json scale_row_json(const ScaleRow& r) {
    nlohmann::ordered_json j = {{"scene", r.scene}, {"engine", r.engine}, {"config", r.config}};
    if (r.threads) j["threads"] = *r.threads;
    j["status"] = r.status;
    if (r.status != "failed") {
        j["bodies"] = r.bodies;
        j["seconds"] = r.seconds;
        j["ticks"] = r.ticks;
        if (r.steps) j["steps"] = *r.steps;
        j["ms_per_tick"] = r.ms_per_tick;
        j["penetration_m"] = r.penetration_m ? nlohmann::ordered_json(*r.penetration_m) : nlohmann::ordered_json();
        j["moving"] = r.moving;
        j["kinetic_J"] = r.kinetic_J;
        j["top_moved_m"] = r.top_moved_m ? nlohmann::ordered_json(*r.top_moved_m) : nlohmann::ordered_json();
        if (r.sleeping) j["sleeping"] = *r.sleeping;
        if (r.peak_kb) j["peak_memory_mb"] = double(r.peak_kb) * 1024.0 / 1e6;
    }
    if (!r.note.empty()) j["note"] = r.note;
    return j;
}

// Three significant figures, whole numbers from 1,000 up: 0.352, 20.7, 726, 1404.
std::string sig3(double value) {
    char text[32];
    if (std::abs(value) >= 1000.0) std::snprintf(text, sizeof text, "%.0f", value);
    else std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

// A length in mm to the hundredth (what the tables need to tell 0.2 mm of slop from none),
// three figures from 10 mm up.
std::string mm(double metres) {
    char text[32];
    const double value = metres * 1e3;
    if (std::abs(value) >= 10.0) return sig3(value);
    std::snprintf(text, sizeof text, "%.2f", value);
    return text;
}

void print_scale_header() {
    std::printf("%-25s %-23s %6s %5s %6s %10s %8s %7s %7s %10s %8s\n", "scene", "run", "bodies", "s", "ticks", "ms/tick",
                "depth mm", "moving", "asleep", "KE left J", "top mm");
}

void print_scale_row(const ScaleRow& r) {
    const std::string run = r.engine + ", " + r.config;
    if (r.status == "failed") {
        std::printf("%-25s %-23s  failed: %s\n", r.scene.c_str(), run.c_str(), r.note.c_str());
        return;
    }
    const std::string depth = r.penetration_m ? mm(*r.penetration_m) : "-", top = r.top_moved_m ? mm(*r.top_moved_m) : "-";
    const std::string asleep = r.sleeping ? std::to_string(*r.sleeping) : "-";
    std::printf("%-25s %-23s %6d %5.3g %6d %10.4g %8s %7d %7s %10.3g %8s%s\n", r.scene.c_str(), run.c_str(), r.bodies,
                r.seconds, r.ticks, r.ms_per_tick, depth.c_str(), r.moving, asleep.c_str(), r.kinetic_J, top.c_str(),
                r.status == "diverged" ? "  DIVERGED" : "");
}


// A comma-separated list of scene names, given to `option`.
std::vector<std::string> parse_scenes(const std::string& option, std::string_view text) {
    std::vector<std::string> scenes;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string_view name = text.substr(start, comma - start);
        if (name.empty()) throw UsageError(option + ": an empty name in '" + std::string(text) + "'");
        scenes.emplace_back(name);
        start = comma + 1;
    }
    return scenes;
}

// The peer's three configurations, as the table has them.
struct PeerConfig {
    const char* key;
    const char* label;
};
constexpr PeerConfig kPeerConfigs[] = {
    {"iterations", "10 iterations"}, {"substeps", "2 substeps"}, {"sleeping", "sleeping on"}};

// The section: every scene at each thread count, then the peer's three runs of it, each row as
// it comes; then two tables, ms per tick side by side and the soundness figures, in Markdown (the
// tables in tests/benchmarks/README.md are this output). Returns the rows as JSON.
nlohmann::ordered_json scale_section(const std::vector<std::string>& scenes, double seconds_override,
                                     const std::vector<int>& thread_counts, bool use_peer, bool json) {
    const std::string peer = use_peer ? find_peer() : std::string();
    std::ostream& log = json ? std::cerr : std::cout;
    const double load_before = load_average();
    if (!json) {
        std::cout << "\nrigid bodies at scale: each scene simulated for " << (seconds_override > 0.0 ? sig3(seconds_override) : "10")
                  << " s" << (seconds_override > 0.0 ? "" : " (3 s for pyramid:20)")
                  << ", ms per tick over the whole run (wall clock of the ticks only, dt 0.02 s);\n"
                     "after it: depth = the deepest point of any body below the ground (its collision shape's support\n"
                     "point), moving = bodies with a point faster than 1 cm/s (|v| + |w| r), asleep = bodies the engine\n"
                     "has put to sleep (softbody: the sleeping key, on by default), KE = kinetic energy left,\n"
                     "top = how far a pyramid's top box went from its start.\n";
        if (!peer.empty()) {
            std::cout << "Bullet runs: " << peer << " (the same scenes built in Bullet; see tests/benchmarks/README.md).\n";
        } else if (use_peer) {
            std::cout << "Bullet comparison skipped: softbody_peer_bullet was not built beside this executable (to get it: "
                         "sudo apt install libbullet-dev, then rebuild)\n";
        } else {
            std::cout << "Bullet comparison left out (--no-peer).\n";
        }
        std::cout << "\n";
        print_scale_header();
    } else if (peer.empty() && use_peer) {
        std::cerr << "Bullet comparison skipped: softbody_peer_bullet was not built (sudo apt install libbullet-dev, rebuild)\n";
    }
    std::vector<ScaleRow> rows;
    for (const std::string& scene : scenes) {
        const double seconds = seconds_override > 0.0 ? seconds_override : default_scale_seconds(scene);
        auto add = [&](ScaleRow row) {
            if (!json) print_scale_row(row);
            else log << "  " << row.scene << ", " << row.engine << ", " << row.config << ": " << sig3(row.ms_per_tick) << " ms/tick\n";
            std::cout.flush();
            rows.push_back(std::move(row));
        };
        for (int t : thread_counts) add(softbody_row(scene, measure_scale(scene, t, seconds)));
        // The peer runs each scene as it is (its configurations have sleeping on and off).
        if (!peer.empty() && scene.find('@') == std::string::npos) {
            for (const PeerConfig& c : kPeerConfigs) add(run_peer(peer, scene, c.key, c.label, seconds));
        }
    }

    // The columns of the side-by-side tables, in the order.
    std::vector<std::pair<std::string, std::string>> columns;  // engine, config
    for (int t : thread_counts) columns.emplace_back("softbody", std::to_string(t) + (t > 1 ? " threads" : " thread"));
    if (!peer.empty()) {
        for (const PeerConfig& c : kPeerConfigs) columns.emplace_back("bullet", c.label);
    }
    auto find = [&](const std::string& scene, const std::pair<std::string, std::string>& column) -> const ScaleRow* {
        for (const ScaleRow& r : rows) {
            if (r.scene == scene && r.engine == column.first && r.config == column.second) return &r;
        }
        return nullptr;
    };
    const double load_after = load_average();
    if (!json) {
        std::printf("\nload average (1 min) %.2f before the section, %.2f after, on %d hardware threads\n", load_before,
                    load_after, hardware_threads());
        auto head = [&](const char* first) {
            std::cout << "| scene | bodies | simulated s |";
            for (const auto& [engine, config] : columns) std::cout << " " << (engine == "bullet" ? "Bullet" : "softbody") << ", " << config << " |";
            std::cout << "\n|---|---:|---:|";
            for (std::size_t i = 0; i < columns.size(); ++i) std::cout << (first[0] == 'r' ? "---:|" : "---|");
            std::cout << "\n";
        };
        std::cout << "\nms per tick, whole run:\n\n";
        head("r");
        for (const std::string& scene : scenes) {
            const ScaleRow* any = find(scene, columns.front());
            std::cout << "| `" << scene << "` | " << (any ? any->bodies : 0) << " | " << (any ? sig3(any->seconds) : "-") << " |";
            for (const auto& column : columns) {
                const ScaleRow* r = find(scene, column);
                std::cout << " " << (r && r->status == "ok" ? sig3(r->ms_per_tick) : r ? r->status : "-") << " |";
            }
            std::cout << "\n";
        }
        std::cout << "\nafter the run: deepest point below the ground, bodies still moving, bodies asleep, kinetic energy\n"
                     "left (and the pyramid's top box: how far it went):\n\n";
        head("l");
        for (const std::string& scene : scenes) {
            const ScaleRow* any = find(scene, columns.front());
            std::cout << "| `" << scene << "` | " << (any ? any->bodies : 0) << " | " << (any ? sig3(any->seconds) : "-") << " |";
            for (const auto& column : columns) {
                const ScaleRow* r = find(scene, column);
                if (!r || r->status == "failed") {
                    std::cout << " - |";
                    continue;
                }
                std::cout << " " << (r->penetration_m ? mm(*r->penetration_m) + " mm, " : "") << r->moving << " moving, ";
                if (r->sleeping) std::cout << *r->sleeping << " asleep, ";
                std::cout << sig3(r->kinetic_J) << " J";
                if (r->top_moved_m) std::cout << ", top " << mm(*r->top_moved_m) << " mm";
                if (r->status != "ok") std::cout << " (" << r->status << ")";
                std::cout << " |";
            }
            std::cout << "\n";
        }
    }

    nlohmann::ordered_json out = {
        {"seconds_override", seconds_override > 0.0 ? nlohmann::ordered_json(seconds_override) : nlohmann::ordered_json()},
        {"moving_speed_mps", kMovingSpeed},
        {"load_average_before", load_before},
        {"load_average_after", load_after},
        {"peer", peer.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(peer)},
        {"rows", nlohmann::ordered_json::array()}};
    for (const ScaleRow& r : rows) out["rows"].push_back(scale_row_json(r));
    return out;
}

// =============================================================================================
// A busy machine: the same kinds of scenes while another program spins on one core
// =============================================================================================
// On a machine shared with other programs a thread of the pool may wait for the system to give
// it a core; a batch that waited for it lost a whole time slice, and a tick has hundreds of
// batches. Here a child process spins on one core (BusyCore) while each scene runs a fixed number
// of ticks at 1 thread and at --threads, by turns, `repeats` times, each run in a child of its
// own; the row gives the median wall clock of the ticks at each count and their ratio, threads
// over one. Above 1 the second thread costs time; the pool's aim is at most 1.15 on every scene.

struct BusyScene {
    std::string name;  // a generated name, a bundled scene file's name, or kBallOnPyramid
    int ticks = 0;     // a run's ticks: a second or so of wall clock on one thread, with the core busy
};

// A soft ball (ball:3, 642 particles) dropped onto a small pyramid of rigid boxes (pyramid:3): a
// soft body on rigid bodies with few of either, where most batches are a few microseconds of work.
const std::string kBallOnPyramid = "ball:3 on pyramid:3";

// One scene of each kind: soft clouds, soft bodies stacked, piles, pyramids, soft on rigid.
const std::vector<BusyScene> kBusyScenes{
    {"cloud:2500", 60},   {"soft_stack.json", 500},      {"pile:100", 150},           {"boxes:1000", 50},
    {"pyramid:10", 40},   {"pile:100+cloud:300", 100},   {kBallOnPyramid, 200},
};

Scene busy_scene(const std::string& name) {
    if (name == kBallOnPyramid) {
        Scene scene = load_scene("pyramid:3+ball:3");
        scene.soft_bodies.front().position = Vec3{0.0f, 0.0f, 4.2f};  // 0.7 m above the top box (its top at 3 m)
        return scene;
    }
    if (std::filesystem::path(name).extension() == ".json" && !std::filesystem::exists(name)) {
        return load_scene((std::filesystem::path(assets_dir()) / "scenes" / name).string());
    }
    return load_scene(name);
}

// One run. Plain data: it crosses a pipe from the child process that measured it.
struct BusyRun {
    int measured = 0;
    int diverged = 0;
    int threads = 1;
    int ticks = 0;
    double seconds = 0.0;  // wall clock of the ticks
    std::uint64_t hash = 0;
    long peak_kb = 0;
    char note[240] = {};
};

BusyRun measure_busy(const std::string& name, int threads, int ticks) {
    return in_child<BusyRun>([&]() {
        BusyRun r;
        World world(busy_scene(name), WorldOptions{threads, false});
        r.threads = world.threads();
        const auto start = Clock::now();
        for (; r.ticks < ticks && world.status() == Status::Ok; ++r.ticks) world.tick();
        r.seconds = seconds_since(start);
        r.hash = world.state_hash();
        if (world.status() != Status::Ok) {
            r.diverged = 1;
            std::snprintf(r.note, sizeof r.note, "%s", world.divergence().c_str());
        }
        r.measured = 1;
        return r;
    });
}

double median_of(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t h = values.size() / 2;
    return values.size() % 2 ? values[h] : 0.5 * (values[h - 1] + values[h]);
}

// The section: every scene's runs with the core busy, each row as it comes. Returns the rows as JSON.
nlohmann::ordered_json busy_section(const std::vector<BusyScene>& scenes, int threads, int repeats, bool json) {
    const double load_before = load_average();
    if (!json) {
        std::printf("\nbusy machine: another process spins on one core while each scene runs its ticks at 1 and at %d\n"
                    "threads, by turns, %d time%s; seconds are the wall clock of the ticks, the median of the runs;\n"
                    "ratio = %d threads / 1 thread (above 1: the threads cost time; the aim is at most 1.15).\n\n",
                    threads, repeats, repeats > 1 ? "s" : "", threads);
        std::printf("%-22s %6s %12s %12s %7s  %s\n", "scene", "ticks", "1 thread s", (std::to_string(threads) + " threads s").c_str(),
                    "ratio", "runs (1 | more)");
    }
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    std::optional<BusyCore> busy;
    try {
        busy.emplace();
    } catch (const std::exception& e) {
        if (!json) std::printf("busy machine skipped: %s\n", e.what());
        return {{"skipped", e.what()}};
    }
    {
        for (const BusyScene& scene : scenes) {
            std::vector<double> one, many;
            std::vector<std::uint64_t> hashes;
            std::string failure;
            for (int r = 0; r < repeats && failure.empty(); ++r) {
                for (int t : {1, threads}) {
                    const BusyRun run = measure_busy(scene.name, t, scene.ticks);
                    if (!run.measured || run.diverged) {
                        failure = run.note[0] ? run.note : "failed";
                        break;
                    }
                    (t == 1 ? one : many).push_back(run.seconds);
                    hashes.push_back(run.hash);
                }
            }
            nlohmann::ordered_json row = {{"scene", scene.name}, {"ticks", scene.ticks}, {"threads", threads}};
            if (!failure.empty()) {
                row["status"] = "failed";
                row["note"] = failure;
                if (!json) std::printf("%-22s %6d  failed: %s\n", scene.name.c_str(), scene.ticks, failure.c_str());
                rows.push_back(row);
                continue;
            }
            const double m1 = median_of(one), mn = median_of(many);
            const bool same = std::all_of(hashes.begin(), hashes.end(), [&](std::uint64_t h) { return h == hashes.front(); });
            row["status"] = "ok";
            row["seconds_1_thread"] = m1;
            row["seconds_threads"] = mn;
            row["ratio"] = mn / m1;
            row["runs_1_thread"] = one;
            row["runs_threads"] = many;
            row["same_state_hash"] = same;
            if (!json) {
                std::string runs;
                char text[32];
                for (double v : one) std::snprintf(text, sizeof text, " %.3g", v), runs += text;
                runs += " |";
                for (double v : many) std::snprintf(text, sizeof text, " %.3g", v), runs += text;
                std::printf("%-22s %6d %12.3f %12.3f %7.2f %s%s\n", scene.name.c_str(), scene.ticks, m1, mn, mn / m1, runs.c_str(),
                            same ? "" : "  (state hashes differ!)");
            } else {
                std::cerr << "  busy " << scene.name << ": " << sig3(m1) << " s at 1 thread, " << sig3(mn) << " s at " << threads
                          << "\n";
            }
            std::cout.flush();
            rows.push_back(row);
        }
    }
    busy.reset();
    const double load_after = load_average();
    if (!json) {
        std::printf("\nload average (1 min, the spinning process included) %.2f before the section, %.2f after, on %d hardware threads\n",
                    load_before, load_after, hardware_threads());
    }
    return {{"threads", threads}, {"repeats", repeats}, {"load_average_before", load_before}, {"load_average_after", load_after},
            {"rows", rows}};
}

// The pair kernel alone, every tile variant this CPU runs, against this CPU's peak: the peak's
// rows and the kernel's, as JSON (and as tables unless `json`).
struct KernelSection {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    nlohmann::ordered_json peak = nlohmann::ordered_json::array();
};
KernelSection kernel_section(const std::vector<std::size_t>& sizes, const std::vector<int>& thread_counts, double budget,
                             bool quick, bool json) {
    KernelSection out;
    nlohmann::ordered_json& kernel_rows = out.rows;
    nlohmann::ordered_json& peak_json = out.peak;
    const std::vector<PairKernelVariant> variants = [] {
        std::vector<PairKernelVariant> here;
        for (auto v : {PairKernelVariant::Scalar, PairKernelVariant::Avx2, PairKernelVariant::Avx512, PairKernelVariant::WasmSimd128}) {
            if (PairForceKernel::supported(v)) here.push_back(v);
        }
        return here;
    }();
    {
        // The peak: independent multiply-add chains at each width, as the tiles issue them.
        std::vector<Peak> peaks;
        const double probe_seconds = quick ? 0.05 : 0.25;
        for (PairKernelVariant v : variants) {
            for (int t : thread_counts) peaks.push_back({v, t, PairForceKernel::peak_flops(v, t, probe_seconds)});
        }
        auto peak_of = [&](PairKernelVariant v, int t) {
            for (const Peak& p : peaks) {
                if (p.variant == v && p.threads == t) return p.flops;
            }
            return 0.0;
        };
        for (const Peak& p : peaks) {
            peak_json.push_back({{"tiles", PairForceKernel::name(p.variant)}, {"width", width_of(p.variant)},
                                 {"threads", p.threads}, {"gflops", p.flops / 1e9}});
        }
        if (!json) {
            std::cout << "\nthis CPU's peak (independent multiply-add chains, " << (quick ? "0.05" : "0.25")
                      << " s of short bursts per row, median burst; a fused multiply-add is 2 flops):\n";
            for (const Peak& p : peaks) {
                std::printf("  %-7s %-7s %d thread%s %8.1f GFLOP/s\n", width_of(p.variant), PairForceKernel::name(p.variant),
                            p.threads, p.threads > 1 ? "s" : " ", p.flops / 1e9);
            }
            std::cout << "\npair kernel alone (PairForceKernel::compute on a moving cloud, no tick around it). flops/pair\n"
                         "is counted in the tile as written (pair_forces.cpp): 9 subtractions, 3 dot products (l^2, |r_j - r_i|^2\n"
                         "for the rest length, (v_j - v_i).d), a square root for l0, 1/sqrt(l^2) and its Newton step, the\n"
                         "force scale, 6 multiply-adds onto the two particles; % peak = pairs/s x flops/pair over the peak\n"
                         "of the tile's width at the same thread count:\n";
            std::printf("%-8s %6s %3s %6s %19s %9s %6s %8s %7s\n", "tiles", "N", "thr", "calls", "ms/call (best)", "pairs/s",
                        "flops", "GFLOP/s", "% peak");
        }
        for (std::size_t n : sizes) {
            for (PairKernelVariant variant : variants) {
                for (int t : thread_counts) {
                    const Measurement m = measure_kernel(variant, n, t, 0.25 * budget);
                    const double rate = m.measured ? m.pairs_per_tick / m.median_s : 0.0;
                    const int flops = PairForceKernel::flops_per_pair(variant);
                    const double peak = peak_of(variant, t), gflops = rate * flops / 1e9;
                    const double fraction = peak > 0.0 ? rate * flops / peak : 0.0;
                    kernel_rows.push_back({{"tiles", PairForceKernel::name(variant)}, {"particles", n}, {"threads", t},
                                           {"calls_measured", m.ticks}, {"ms_per_call_median", ms(m.median_s)},
                                           {"ms_per_call_best", ms(m.best_s)}, {"pairs_per_second", rate},
                                           {"flops_per_pair", flops}, {"gflops", gflops}, {"peak_gflops", peak / 1e9},
                                           {"fraction_of_peak", fraction}});
                    if (!json) {
                        char timing[40];
                        std::snprintf(timing, sizeof timing, "%.4g (%.4g)", ms(m.median_s), ms(m.best_s));
                        std::printf("%-8s %6zu %3d %6d %19s %9s %6d %8.1f %6.0f%%\n", PairForceKernel::name(variant), n, t,
                                    m.ticks, timing, si(rate).c_str(), flops, gflops, 100.0 * fraction);
                    }
                }
            }
        }
        std::cout.flush();
    }
    return out;
}

// The largest cloud that runs in real time (a tick in at most dt) at `threads`, from the cloud
// rows measured and a bisection between them; null when none of them does.
nlohmann::ordered_json search_real_time(const std::vector<Row>& rows, const std::string& fast_name, double dt, int threads,
                                        double budget, bool quick, bool json, std::ostream& log) {
    nlohmann::ordered_json real_time = nullptr;
    {
        if (!json) {
            std::cout << "\nsearching the largest cloud that runs in real time: median tick within " << dt
                      << " s (fast kernel, " << threads << " threads; a size that misses it although some of its ticks"
                      << " made it is measured once more)...\n";
        }
        std::size_t lo = 0, hi = kMaxParticles + 1;  // lo runs in real time, hi does not (none yet: above the max)
        Measurement at_lo, at_hi;
        for (const Row& r : rows) {
            if (r.scene.rfind("cloud:", 0) != 0 || r.kernel != fast_name || r.m.threads != threads || !r.m.measured || r.m.diverged) continue;
            if (r.m.median_s <= dt && r.n > lo) {
                lo = r.n;
                at_lo = r.m;
            }
            if (r.m.median_s > dt && r.n < hi) {
                hi = r.n;
                at_hi = r.m;
            }
        }
        const std::size_t resolution = quick ? 500 : 50;
        const double probe_budget = quick ? 0.1 : std::max(0.3, 0.4 * budget);
        if (lo > 0 && hi > lo) {
            auto probe = [&](std::size_t n) {
                Measurement m = measure(Kernel::Fast, cloud(n), threads, probe_budget);
                if (m.measured && m.median_s > dt && m.best_s <= dt) {
                    // Some ticks were fast enough: other work may have slowed the rest. Once more.
                    const Measurement again = measure(Kernel::Fast, cloud(n), threads, probe_budget);
                    if (again.measured && again.median_s < m.median_s) m = again;
                }
                const bool real = m.measured && !m.diverged && m.median_s <= dt;
                log << "  N " << n << ": " << m.substeps << " substeps, " << ms(m.median_s) << " ms/tick"
                    << (real ? " (real time)" : "") << "\n";
                if (real) lo = n, at_lo = m;
                else hi = n, at_hi = m;
            };
            while (hi > kMaxParticles && lo < kMaxParticles) probe(std::min(2 * lo, kMaxParticles));  // find a too-slow size
            while (hi <= kMaxParticles && hi - lo > resolution) probe((lo + hi) / 2 / 10 * 10);
            real_time = {{"largest_particles", lo},   {"substeps", at_lo.substeps},
                         {"ms_per_tick", ms(at_lo.median_s)}, {"threads", at_lo.threads},
                         {"first_too_slow", hi},      {"first_too_slow_substeps", at_hi.substeps},
                         {"first_too_slow_ms_per_tick", ms(at_hi.median_s)}, {"resolution", resolution}};
            if (!json) {
                std::printf("largest real-time cloud: N = %zu with %d substeps, %.2f ms a tick (%.1f ticks/s)", lo,
                            at_lo.substeps, ms(at_lo.median_s), 1.0 / at_lo.median_s);
                if (hi <= kMaxParticles) std::printf("; N = %zu takes %.2f ms (%d substeps)", hi, ms(at_hi.median_s), at_hi.substeps);
                std::printf("\n");
            }
        } else if (!json) {
            std::cout << "none of the measured sizes runs in real time\n";
        }
    }
    return real_time;
}

// What the pair forces need at 10,000 and 20,000 particles, by kernel (MB).
nlohmann::ordered_json memory_section(bool one_section, bool json) {
    nlohmann::ordered_json memory = nlohmann::ordered_json::array();
    if (!json && !one_section) std::cout << "\nmemory the pair forces need (MB, 10^6 bytes):\n";
    for (std::size_t n : {std::size_t(10000), std::size_t(20000)}) {
        if (one_section) break;
        const double mb = 1e6;
        const double kernel = double(PairForceKernel::memory_bytes(n)) / mb;
        const double stored_l0 = double(n) * double(n - 1) / 2.0 * 4.0 / mb;
        const double tables = 3.0 * double(n) * double(n) * 4.0 / mb;
        memory.push_back({{"particles", n}, {"fast_kernel_mb", kernel}, {"stored_rest_lengths_mb", stored_l0},
                          {"baseline_tables_mb", tables}});
        if (!json) {
            std::printf("  N %5zu: fast kernel %.1f (packed state + per-tile partial forces; rest lengths recomputed); "
                        "one float l0 per pair would add %.0f; the baseline's N x N k, c, l0 tables take %.0f\n",
                        n, kernel, stored_l0, tables);
        }
    }
    return memory;
}

}  // namespace

int bench_command(int argc, char** argv) {
    CLI::App app("Times the physics alone on the scenes the app opens: the CPU's peak, whole ticks of cloud:N at 1 and\n"
                 "all threads against the reference kernel and Listing 8 transcribed, the pair kernel alone, the bundled\n"
                 "meshes, pile:100 with and without a cloud, the largest cloud that runs in real time, rigid bodies at scale,\n"
                 "and the same kinds of scenes with another process busy on one core (tests/benchmarks/README.md).",
                 "softbody bench");
    configure(app);
    bool quick = false, json = false, no_meshes = false, no_bodies = false, no_search = false, no_kernels = false;
    bool no_scale = false, scale_only = false, no_peer = false, no_busy = false, busy_only = false;
    std::string sizes_text, scale_text, busy_text;
    std::int64_t busy_ticks = 0, busy_repeats = 0;  // 0: the defaults
    double scale_seconds = 0.0;  // 0: each scene's default
    double budget = -1.0;
    int threads = hardware_threads();
    std::int64_t baseline_max = -1, reference_max = -1;
    app.add_flag("--quick", quick, "a few seconds: small sizes and short measurements (for CI)");
    app.add_flag("--json", json, "one JSON object instead of the tables");
    app.add_option("--sizes", sizes_text, "cloud sizes, as cloud:N scenes (default 500,1000,2500,5000,10000; --quick 500,1000,2500)")
        ->type_name("N,N,...");
    add_number(app, "--seconds", budget, 0.0, 3600.0, "wall time for each measurement (default 1; --quick 0.15)")->type_name("S");
    add_whole(app, "--threads", threads, 1, 256,
              "threads for the fast kernel's threaded rows (default " + std::to_string(threads) + ", this machine's)");
    add_whole(app, "--baseline-max", baseline_max, 0, 20000,
              "largest N for Listing 8 transcribed (default 5000, --quick 1000: its tables take 12 N^2 bytes)");
    add_whole(app, "--reference-max", reference_max, 0, 20000, "largest N for the reference kernel (default 10000, --quick 1000)");
    app.add_flag("--no-kernels", no_kernels, "skip the peak probe and the pair kernel alone (every tile variant)");
    app.add_flag("--no-meshes", no_meshes, "skip the bundled meshes (scene files with a soft body and no rigid bodies)");
    app.add_flag("--no-bodies", no_bodies, "skip the rigid and mixed scenes (pile:100, pile:100+cloud:1000, ball on pyramid:3)");
    app.add_flag("--no-search", no_search, "skip the search for the largest cloud that runs in real time");
    app.add_flag("--no-scale", no_scale,
                 "skip \"rigid bodies at scale\": piles and pyramids timed over whole runs, beside Bullet where its peer "
                 "(softbody_peer_bullet) was built");
    app.add_flag("--scale-only", scale_only, "run only that section");
    app.add_option("--scale-scenes", scale_text,
                   "its scenes, each NAME or NAME@KEY=VALUE (a key set as --set sets it) (default " +
                       [] {
                           std::string names;
                           for (const std::string& name : kScaleScenes) names += (names.empty() ? "" : ",") + name;
                           return names;
                       }() +
                       "; --quick boxes:100,pyramid:10)")
        ->type_name("NAME,...");
    add_number(app, "--scale-seconds", scale_seconds, 0.02, 3600.0,
               "simulated seconds of each of its runs (default 10, 3 for pyramid:20 and up; --quick 0.4)")
        ->type_name("S");
    app.add_flag("--no-peer", no_peer, "leave the peer out even where it was built");
    app.add_flag("--no-busy", no_busy,
                 "skip \"busy machine\": soft clouds, piles, pyramids and soft on rigid at 1 and --threads threads while "
                 "another process spins on one core, with the ratio of their times");
    app.add_flag("--busy-only", busy_only, "run only that section");
    app.add_option("--busy-scenes", busy_text,
                   "its scenes: generated names, bundled scene files or '" + kBallOnPyramid + "' (default all of " +
                       [] {
                           std::string names;
                           for (const BusyScene& b : kBusyScenes) names += (names.empty() ? "" : ",") + b.name;
                           return names;
                       }() +
                       "; --quick two)")
        ->type_name("NAME,...");
    add_whole(app, "--busy-ticks", busy_ticks, 1, 1'000'000,
              "ticks of each of its runs (default each scene's, about a second on one thread; --quick a tenth)")
        ->type_name("N");
    add_whole(app, "--busy-repeats", busy_repeats, 1, 100, "its runs at each thread count, by turns (default 3, --quick 1)")
        ->type_name("N");
    app.footer(exit_codes_help(false));
    if (!parse(app, argc, argv, 2)) return kOk;
    bool meshes = !no_meshes, bodies = !no_bodies, search = !no_search, kernels = !no_kernels;
    const bool scale = !no_scale, use_peer = !no_peer;
    std::vector<std::size_t> sizes;
    if (!sizes_text.empty()) sizes = parse_sizes(sizes_text);
    std::vector<std::string> scale_scenes;
    if (!scale_text.empty()) scale_scenes = parse_scenes("--scale-scenes", scale_text);
    if (sizes.empty()) sizes = quick ? std::vector<std::size_t>{500, 1000, 2500} : std::vector<std::size_t>{500, 1000, 2500, 5000, 10000};
    if (budget < 0.0) budget = quick ? 0.15 : 1.0;
    if (baseline_max < 0) baseline_max = quick ? 1000 : 5000;
    if (reference_max < 0) reference_max = quick ? 1000 : 10000;
    const std::size_t mesh_max = quick ? 3000 : kMaxParticles;
    if (scale_only && !scale) throw UsageError("--scale-only and --no-scale: choose one");
    if (busy_only && no_busy) throw UsageError("--busy-only and --no-busy: choose one");
    if (busy_only && scale_only) throw UsageError("--busy-only and --scale-only: choose one");
    const bool busy = !no_busy && !scale_only, scale_section_on = scale && !busy_only;
    const bool one_section = scale_only || busy_only;
    std::vector<BusyScene> busy_scenes;
    for (const std::string& name : busy_text.empty() ? std::vector<std::string>{} : parse_scenes("--busy-scenes", busy_text)) {
        const auto known = std::find_if(kBusyScenes.begin(), kBusyScenes.end(), [&](const BusyScene& b) { return b.name == name; });
        busy_scenes.push_back({name, known != kBusyScenes.end() ? known->ticks : 100});
        busy_scene(name);  // refused here, in one line, rather than in every child that would build it
    }
    if (busy_scenes.empty()) {
        busy_scenes = kBusyScenes;
        if (quick) busy_scenes = {kBusyScenes[5], kBusyScenes[6]};  // the two soft bodies on rigid ones
    }
    for (BusyScene& b : busy_scenes) b.ticks = busy_ticks > 0 ? int(busy_ticks) : quick ? std::max(5, b.ticks / 10) : b.ticks;
    if (busy_repeats == 0) busy_repeats = quick ? 1 : 3;
    // --quick: a smoke of the section, two of its scenes for 0.4 s each, unless told otherwise.
    if (scale_scenes.empty()) scale_scenes = quick ? std::vector<std::string>{"boxes:100", "pyramid:10"} : kScaleScenes;
    if (quick && scale_seconds == 0.0) scale_seconds = 0.4;
    if (scale_only || busy_only) sizes.clear(), kernels = meshes = bodies = search = false;
    for (const std::string& name : scale_scenes) {
        // Refused here, in one line, rather than in every child that would build it.
        Scene scene;
        try {
            scene = load_scale_scene(name);
        } catch (const UsageError&) {
            throw;
        } catch (const std::exception& e) {
            const std::string what = e.what();
            throw UsageError("--scale-scenes: " + (what.rfind(name, 0) == 0 ? what : name + ": " + what));
        }
        if (scene.rigid_bodies.empty()) throw UsageError("--scale-scenes: " + name + " has no rigid bodies");
    }

    const Scene cloud_scene = load_scene(cloud(2));  // what a cloud:N scene runs with: Listing 8's constants
    const SoftBodyDef& defaults = cloud_scene.soft_bodies.front();
    const double dt = cloud_scene.settings.dt;
    const std::string fast_name = std::string("fast (") + PairForceKernel::name(PairForceKernel::best_variant()) + ")";
    const auto bench_start = Clock::now();
    std::ostream& log = json ? std::cerr : std::cout;  // progress goes to stderr with --json

    if (!json && !one_section) {
        std::cout << "softbody bench: physics only, dt " << dt << " s, k " << defaults.stiffness << " N/m, c "
                  << defaults.damping << " kg/s, m " << defaults.particle_mass
                  << " kg, substeps picked for stability (auto_substeps)\n"
                  << "fast kernel: " << PairForceKernel::name(PairForceKernel::best_variant()) << " tiles (CPU: avx2+fma "
                  << (PairForceKernel::supported(PairKernelVariant::Avx2) ? "yes" : "no") << ", avx512f "
                  << (PairForceKernel::supported(PairKernelVariant::Avx512) ? "yes" : "no") << "), " << hardware_threads()
                  << " hardware threads\n"
                  << "times are the median (and best) of the ticks measured, about " << budget
                  << " s of each; other work on this machine shows up in them: repeat for steady figures.\n"
                  << "pairs/s counts unique pairs, N(N-1)/2 per substep; evals/s counts pair evaluations made (the\n"
                  << "baseline evaluates every pair from both ends, N(N-1) per substep); x realtm = 0.02 s / (ms/tick).\n\n";
        print_header(std::cout);
    }

    // --- Clouds ------------------------------------------------------------------------------
    std::vector<Row> rows;
    auto add = [&](Row row) {
        if (!json) print_row(std::cout, row, dt);
        rows.push_back(std::move(row));
    };
    std::vector<int> thread_counts{1};
    if (threads > 1) thread_counts.push_back(threads);
    for (std::size_t n : sizes) {
        const std::string name = cloud(n);
        for (int t : thread_counts) add({name, n, fast_name, measure(Kernel::Fast, name, t, budget)});
        if (n <= std::size_t(reference_max)) add({name, n, "reference", measure(Kernel::Reference, name, 1, budget)});
        if (n <= std::size_t(baseline_max)) add({name, n, "baseline", measure(Kernel::Baseline, name, 1, budget)});
    }

    // --- The pair kernel alone, every tile variant this CPU runs, against this CPU's peak ---------
    KernelSection kernel_alone;
    if (kernels) kernel_alone = kernel_section(sizes, thread_counts, budget, quick, json);

    // --- Bundled meshes ------------------------------------------------------------------------
    std::vector<std::string> skipped;
    if (meshes) {
        for (const std::string& file : bundled_mesh_scenes()) {
            const std::string name = std::filesystem::path(file).filename().string();
            std::size_t n = 0;
            try {
                const Scene scene = load_scene(file);
                if (scene.soft_bodies.size() != 1 || !scene.rigid_bodies.empty()) continue;  // not a mesh on its own
                n = World(scene).soft_body(0).particle_count();
            } catch (const std::exception& e) {
                skipped.push_back(name + ": " + e.what());
                continue;
            }
            if (n > mesh_max) {
                skipped.push_back(name + ": " + std::to_string(n) + " particles, above " + std::to_string(mesh_max));
                continue;
            }
            for (int t : thread_counts) add({name, n, fast_name, measure(Kernel::Fast, file, t, budget)});
            if (!quick && n <= 2500) add({name, n, "reference", measure(Kernel::Reference, file, 1, budget)});
        }
    }

    // --- Rigid bodies and contacts: a pile of a hundred, and with a soft body on it ------------
    if (bodies) {
        for (const char* name : {"pile:100", "pile:100+cloud:1000"}) {
            const std::size_t n = std::string_view(name).find("cloud") != std::string_view::npos ? 1000 : 0;
            for (int t : thread_counts) add({name, n, fast_name, measure(Kernel::Fast, name, t, budget, 50)});
        }
        // A soft body resting on rigid bodies, against the two apart.
        for (const auto& [name, ball, pyramid] : {std::tuple{"ball", true, false}, std::tuple{"pyramid:3", false, true},
                                                  std::tuple{"ball on pyramid:3", true, true}}) {
            const std::size_t n = ball ? 162 : 0;
            const bool with_ball = ball, with_pyramid = pyramid;  // (the browser build's clang cannot capture a structured binding)
            for (int t : thread_counts) {
                add({name, n, fast_name, measure_scene(Kernel::Fast, [&] { return ball_on_pyramid(with_ball, with_pyramid); }, t, budget, 100)});
            }
        }
        // Soft contacts: two 2,906-particle cubes, one on the other, against the two apart.
        for (bool touching : {false, true}) {
            const std::string name = touching ? "2 cubes touching" : "2 cubes apart";
            for (int t : thread_counts) {
                add({name, 5812, fast_name, measure_scene(Kernel::Fast, [&] { return two_cubes(touching); }, t, budget, 25)});
            }
        }
    }

    // --- Ratios, fast against baseline and reference, from the rows above ----------------------
    auto find = [&](std::size_t n, const std::string& kernel, int t) -> const Measurement* {
        for (const Row& r : rows) {
            if (r.scene == cloud(n) && r.kernel == kernel && r.m.threads == t && r.m.measured) return &r.m;
        }
        return nullptr;
    };
    nlohmann::ordered_json ratios = nlohmann::ordered_json::array();
    std::ostringstream ratio_text;
    for (std::size_t n : sizes) {
        const Measurement* base = find(n, "baseline", 1);
        const Measurement* ref = find(n, "reference", 1);
        for (int t : thread_counts) {
            const Measurement* fast = find(n, fast_name, t);
            if (!fast) continue;
            const double fast_rate = fast->pairs_per_tick / fast->median_s;
            nlohmann::ordered_json r = {{"particles", n}, {"threads", t}, {"fast_pairs_per_second", fast_rate}};
            char line[256];
            int len = std::snprintf(line, sizeof line, "  N %6zu, fast at %d thread%s: %s pairs/s", n, t, t > 1 ? "s" : " ",
                                    si(fast_rate).c_str());
            if (base) {
                const double eval_ratio = fast_rate / (base->evals_per_tick / base->median_s);
                const double time_ratio = base->median_s / fast->median_s;
                r["vs_baseline_evaluation_rate"] = eval_ratio;
                r["vs_baseline_tick_time"] = time_ratio;
                len += std::snprintf(line + len, sizeof line - len, "; %.0fx the baseline's evals/s (%.0fx faster per tick)",
                                     eval_ratio, time_ratio);
            }
            if (ref) {
                r["vs_reference_tick_time"] = ref->median_s / fast->median_s;
                std::snprintf(line + len, sizeof line - len, "; %.1fx faster than the reference", ref->median_s / fast->median_s);
            }
            ratios.push_back(r);
            ratio_text << line << "\n";
        }
    }
    if (!json && !one_section) std::cout << "\nfast kernel against the others (medians from the rows above):\n" << ratio_text.str();

    // --- The largest cloud that runs in real time (a tick in at most dt), all threads ----------
    const nlohmann::ordered_json real_time =
        search ? search_real_time(rows, fast_name, dt, threads, budget, quick, json, log) : nlohmann::ordered_json(nullptr);

    // --- Memory ---------------------------------------------------------------------------------
    const nlohmann::ordered_json memory = memory_section(one_section, json);
    if (!json && !skipped.empty()) {
        std::cout << "\nmeshes not benched:\n";
        for (const std::string& s : skipped) std::cout << "  " << s << "\n";
    }

    // --- Rigid bodies at scale, beside the peer ---------------------------------------------------
    nlohmann::ordered_json scale_json = nullptr;
    if (scale_section_on) scale_json = scale_section(scale_scenes, scale_seconds, thread_counts, use_peer, json);

    // --- The same kinds of scenes on a busy machine ------------------------------------------------
    nlohmann::ordered_json busy_json = nullptr;
    if (busy) busy_json = busy_section(busy_scenes, threads, int(busy_repeats), json);

    const double total = seconds_since(bench_start);
    if (json && scale_only) {
        const nlohmann::ordered_json out = {{"dt", dt}, {"hardware_threads", hardware_threads()}, {"scale", scale_json},
                                            {"wall_seconds", total}};
        std::cout << out.dump(2) << std::endl;
    } else if (json && busy_only) {
        const nlohmann::ordered_json out = {{"dt", dt}, {"hardware_threads", hardware_threads()}, {"busy", busy_json},
                                            {"wall_seconds", total}};
        std::cout << out.dump(2) << std::endl;
    } else if (json) {
        nlohmann::ordered_json rows_json = nlohmann::ordered_json::array();
        for (const Row& r : rows) rows_json.push_back(row_json(r, dt));
        nlohmann::ordered_json out = {
            {"dt", dt},
            {"stiffness", defaults.stiffness},
            {"damping", defaults.damping},
            {"particle_mass", defaults.particle_mass},
            {"fast_variant", PairForceKernel::name(PairForceKernel::best_variant())},
            {"flops_per_pair", {{"avx512", PairForceKernel::flops_per_pair(PairKernelVariant::Avx512)},
                                {"avx2", PairForceKernel::flops_per_pair(PairKernelVariant::Avx2)},
                                {"scalar", PairForceKernel::flops_per_pair(PairKernelVariant::Scalar)},
                                {"counted", "as the tile executes: a fused multiply-add 2, a square root or reciprocal "
                                            "square root 1; 9 subtractions, 3 dot products, sqrt for l0, 1/sqrt(l^2) "
                                            "and its Newton step, the force scale, 6 multiply-adds onto the pair "
                                            "(see pair_forces.cpp)"}}},
            {"hardware_threads", hardware_threads()},
            {"seconds_per_measurement", budget},
            {"quick", quick},
            {"rows", rows_json},
            {"kernel_alone", kernel_alone.rows},
            {"ratios", ratios},
            {"real_time", real_time},
            {"peak", kernel_alone.peak},
            {"memory", memory},
            {"scale", scale_json},
            {"busy", busy_json},
            {"meshes_skipped", skipped},
            {"wall_seconds", total},
        };
        std::cout << out.dump(2) << std::endl;
    } else {
        std::printf("\nbench took %.1f s\n", total);
    }
    return kOk;
}

}  // namespace softbody::app
