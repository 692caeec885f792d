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
//
// Every measurement runs in a child process of its own, so each row's peak memory
// (getrusage's ru_maxrss) is that row's alone.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/mesh.h"
#include "physics/pair_forces.h"
#include "physics/scene_io.h"
#include "physics/world.h"

namespace softbody::app {

namespace {

constexpr const char* kUsage =
    "usage: softbody bench [--quick] [--json] [--sizes N,N,...] [--seconds S] [--threads N]\n"
    "                      [--baseline-max N] [--reference-max N] [--no-kernels] [--no-meshes] [--no-bodies]\n"
    "                      [--no-search]\n"
    "  --quick           a few seconds: small sizes, short measurements (for CI)\n"
    "  --json            print one JSON object instead of the tables\n"
    "  --sizes           cloud sizes, as cloud:N scenes (default 500,1000,2500,5000,10000; --quick\n"
    "                    500,1000,2500)\n"
    "  --seconds         wall time to spend on each measurement (default 1; --quick 0.15)\n"
    "  --threads         threads for the fast kernel's multi-threaded rows (default: all)\n"
    "  --baseline-max    largest N for the baseline transcription (default 5000: its N x N\n"
    "                    tables take 12 N^2 bytes, 1.2 GB at N = 10,000)\n"
    "  --reference-max   largest N for the reference kernel (default 10000)\n"
    "  --no-kernels      skip the table of the pair kernel alone (every tile variant) and the\n"
    "                    peak probe\n"
    "  --no-meshes       skip the bundled meshes (the scene files in assets/scenes with a soft body\n"
    "                    and no rigid bodies)\n"
    "  --no-bodies       skip the rigid and mixed scenes (pile:100, pile:100+cloud:1000)\n"
    "  --no-search       skip the search for the largest real-time cloud";

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
Measurement in_child(const std::function<Measurement()>& measure) {
    int fd[2];
    if (pipe(fd) != 0) throw std::runtime_error("bench: pipe failed");
    std::cout.flush();
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("bench: fork failed");
    if (pid == 0) {
        close(fd[0]);
        Measurement m;
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
    Measurement m;
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
        m = Measurement{};
        std::snprintf(m.note, sizeof m.note, "the measuring process died (%s)",
                      WIFSIGNALED(status) ? strsignal(WTERMSIG(status)) : "no result");
    }
    return m;
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
    return in_child([&]() {
        Measurement m;
        const Scene scene = make();
        World world(make_world_def(scene), WorldOptions{threads, kernel == Kernel::Reference});
        const double n = double(world.soft_body_count() ? world.particle_count() : 0);
        m.substeps = world.substeps_in_use();
        if (n > 0) {
            const Stability s = world.stability();
            m.h_omega = s.h_omega;
            m.limit = s.limit;
        }
        if (kernel == Kernel::Baseline) {
            // The scene's soft body where the World starts it, at the substeps the World picked,
            // so the rows compare like with like.
            const Params& params = scene.params;
            const Vec3Array& x = world.positions();
            std::vector<Vec3> positions(x.size());
            for (std::size_t i = 0; i < x.size(); ++i) positions[i] = x[i];
            baseline::SoftBody body(positions, params.stiffness, params.damping, params.particle_mass);
            const float h = params.dt / float(m.substeps);
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
        SoftBodyScene body;
        body.name = k == 0 ? "lower" : "upper";
        body.params.mesh = "cube:22";
        body.params.scale = 0.6f;
        body.params.max_particles = 0;
        body.params.stiffness = 2.0f;  // soft enough to sag onto the lower cube; few substeps (7)
        body.params.damping = 0.005f;
        body.params.particle_mass = 0.05f;
        body.params.position = touching ? Vec3{0.0f, 0.0f, 0.3f + 0.61f * float(k)} : Vec3{-0.5f + 1.0f * float(k), 0.0f, 0.3f};
        scene.soft_bodies.push_back(body);
    }
    return scene;
}

// The pair kernel alone, one tile variant: compute() on a cloud displaced from rest and moving,
// no tick around it. calls/ticks are force evaluations here.
Measurement measure_kernel(PairKernelVariant variant, std::size_t n, int threads, double budget) {
    return in_child([&]() {
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
        default: return "scalar";
    }
}

}  // namespace

int bench_command(int argc, char** argv) {
    Args args(argc, argv, 2);
    bool quick = false, json = false, meshes = true, bodies = true, search = true, kernels = true;
    std::vector<std::size_t> sizes;
    double budget = -1.0;
    int threads = hardware_threads();
    std::int64_t baseline_max = -1, reference_max = -1;
    while (!args.done()) {
        const std::string_view option = args.next();
        if (option == "--quick") quick = true;
        else if (option == "--json") json = true;
        else if (option == "--no-meshes") meshes = false;
        else if (option == "--no-bodies") bodies = false;
        else if (option == "--no-search") search = false;
        else if (option == "--no-kernels") kernels = false;
        else if (option == "--sizes") sizes = parse_sizes(args.value(option));
        else if (option == "--seconds") budget = parse_double(option, args.value(option), 0.0, 3600.0);
        else if (option == "--threads") threads = static_cast<int>(parse_int(option, args.value(option), 1, 256));
        else if (option == "--baseline-max") baseline_max = parse_int(option, args.value(option), 0, 20000);
        else if (option == "--reference-max") reference_max = parse_int(option, args.value(option), 0, 20000);
        else if (option == "--help" || option == "-h") {
            std::cout << kUsage << "\n";
            return kOk;
        } else {
            throw UsageError("unknown option '" + std::string(option) + "'\n" + kUsage);
        }
    }
    if (sizes.empty()) sizes = quick ? std::vector<std::size_t>{500, 1000, 2500} : std::vector<std::size_t>{500, 1000, 2500, 5000, 10000};
    if (budget < 0.0) budget = quick ? 0.15 : 1.0;
    if (baseline_max < 0) baseline_max = quick ? 1000 : 5000;
    if (reference_max < 0) reference_max = quick ? 1000 : 10000;
    const std::size_t mesh_max = quick ? 3000 : kMaxParticles;

    const Params defaults = load_scene(cloud(2)).params;  // what a cloud:N scene runs with: Listing 8's constants
    const double dt = defaults.dt;
    const std::string fast_name = std::string("fast (") + PairForceKernel::name(PairForceKernel::best_variant()) + ")";
    const auto bench_start = Clock::now();
    std::ostream& log = json ? std::cerr : std::cout;  // progress goes to stderr with --json

    if (!json) {
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
    const std::vector<PairKernelVariant> variants = [] {
        std::vector<PairKernelVariant> here;
        for (auto v : {PairKernelVariant::Scalar, PairKernelVariant::Avx2, PairKernelVariant::Avx512}) {
            if (PairForceKernel::supported(v)) here.push_back(v);
        }
        return here;
    }();
    nlohmann::ordered_json kernel_rows = nlohmann::ordered_json::array();
    nlohmann::ordered_json peak_json = nlohmann::ordered_json::array();
    if (kernels) {
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

    // --- Bundled meshes ------------------------------------------------------------------------
    std::vector<std::string> skipped;
    if (meshes) {
        for (const std::string& file : bundled_mesh_scenes()) {
            const std::string name = std::filesystem::path(file).filename().string();
            std::size_t n = 0;
            try {
                const Scene scene = load_scene(file);
                if (scene.params.mesh.empty() || !scene.rigid_bodies.empty()) continue;  // not a mesh on its own
                n = World(make_world_def(scene)).particle_count();
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
    if (!json) std::cout << "\nfast kernel against the others (medians from the rows above):\n" << ratio_text.str();

    // --- The largest cloud that runs in real time (a tick in at most dt), all threads ----------
    nlohmann::ordered_json real_time = nullptr;
    if (search) {
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

    // --- Memory ---------------------------------------------------------------------------------
    nlohmann::ordered_json memory = nlohmann::ordered_json::array();
    if (!json) std::cout << "\nmemory the pair forces need (MB, 10^6 bytes):\n";
    for (std::size_t n : {std::size_t(10000), std::size_t(20000)}) {
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
    if (!json && !skipped.empty()) {
        std::cout << "\nmeshes not benched:\n";
        for (const std::string& s : skipped) std::cout << "  " << s << "\n";
    }
    const double total = seconds_since(bench_start);
    if (json) {
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
            {"kernel_alone", kernel_rows},
            {"ratios", ratios},
            {"real_time", real_time},
            {"peak", peak_json},
            {"memory", memory},
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
