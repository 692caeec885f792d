// softbody simulate: runs the physics alone and prints one JSON object with the outcome.
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/world.h"

namespace softbody::app {

namespace {

constexpr const char* kUsage =
    "usage: softbody simulate [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... (--seconds T | --ticks N)\n"
    "                         [--dump FILE.csv] [--dump-every K] [--threads N]";

// CSV writer for --dump; reports a failed write (a full disk) instead of losing data quietly.
class Dump {
public:
    explicit Dump(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
        if (!file_) throw InputError(path + ": cannot write the dump file");
        std::fputs("tick,time,particle,x,y,z,vx,vy,vz\n", file_);
    }
    ~Dump() {
        if (file_) std::fclose(file_);
    }
    void write(const World& world) {
        const auto& x = world.positions();
        const auto& v = world.velocities();
        for (std::size_t i = 0; i < world.particle_count(); ++i) {
            std::fprintf(file_, "%" PRIu64 ",%.9g,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", world.ticks(), world.time(), i,
                         x.x[i], x.y[i], x.z[i], v.x[i], v.y[i], v.z[i]);
        }
        if (std::ferror(file_)) throw InputError(path_ + ": writing the dump failed");
    }
    void close() {
        const bool failed = std::fclose(file_) != 0;
        file_ = nullptr;
        if (failed) throw InputError(path_ + ": writing the dump failed");
    }

private:
    std::string path_;
    std::FILE* file_;
};

}  // namespace

int simulate_command(int argc, char** argv) {
    Args args(argc, argv, 2);
    SceneOptions scene;
    std::int64_t ticks = -1;
    double seconds = -1.0;
    std::string dump_path;
    std::int64_t dump_every = 1;
    int threads = hardware_threads();
    while (!args.done()) {
        if (scene.take(args)) continue;
        const std::string_view option = args.next();
        if (option == "--ticks") ticks = parse_int(option, args.value(option), 0, 1'000'000'000);
        else if (option == "--seconds") seconds = parse_double(option, args.value(option), 0.0, 1e7);
        else if (option == "--dump") dump_path = args.value(option);
        else if (option == "--dump-every") dump_every = parse_int(option, args.value(option), 1, 1'000'000'000);
        else if (option == "--threads") threads = static_cast<int>(parse_int(option, args.value(option), 1, 256));
        else if (option == "--help" || option == "-h") {
            std::cout << kUsage << "\n";
            return kOk;
        } else {
            throw UsageError("unknown option '" + std::string(option) + "'\n" + kUsage);
        }
    }
    if ((ticks < 0) == (seconds < 0.0)) throw UsageError(std::string("give exactly one of --seconds or --ticks\n") + kUsage);

    const Params params = scene.resolve();
    World world(params, load_mesh(params.mesh), WorldOptions{threads, false});
    if (seconds >= 0.0) ticks = std::llround(seconds / double(params.dt));

    std::unique_ptr<Dump> dump;
    if (!dump_path.empty()) {
        dump = std::make_unique<Dump>(dump_path);
        dump->write(world);
    }
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t t = 0; t < ticks && world.status() == Status::Ok; ++t) {
        world.tick();
        if (dump && world.status() == Status::Ok && world.ticks() % static_cast<std::uint64_t>(dump_every) == 0) {
            dump->write(world);
        }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (dump) dump->close();

    const Energy e = world.energy();
    const Stability s = world.stability();
    const Vec3 com = world.center_of_mass();
    const bool ok = world.status() == Status::Ok;
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, world.state_hash());
    nlohmann::ordered_json out = {
        {"mesh", params.mesh},
        {"particles", world.particle_count()},
        {"springs", world.spring_count()},
        {"ticks", world.ticks()},
        {"sim_time", world.time()},
        {"wall_time", wall},
        {"threads", world.threads()},
        {"integrator", to_string(params.integrator)},
        {"substeps", s.substeps},
        {"energy", {{"kinetic", e.kinetic}, {"gravity", e.gravity}, {"elastic", e.elastic}, {"total", e.total()}}},
        {"com", {com.x, com.y, com.z}},
        {"min_z", world.min_z()},
        {"stability", s.h_omega},
        {"stability_limit", s.limit},
        {"stable", s.stable},
        {"substeps_needed", s.substeps_needed},
        {"status", ok ? "ok" : "diverged"},
        {"state_hash", hash},
    };
    if (!ok) out["reason"] = world.divergence();
    // A file name need not be UTF-8: its odd bytes are replaced in the summary, not fatal.
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
    if (!ok) {
        std::cerr << "softbody: " << world.divergence() << "\n";
        return kDiverged;
    }
    return kOk;
}

}  // namespace softbody::app
