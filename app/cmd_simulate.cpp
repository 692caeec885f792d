// softbody simulate: runs the physics alone and prints one JSON object with the outcome.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/series.h"
#include "physics/world.h"
#include "world_json.h"

namespace softbody::app {

namespace {

// CSV writer for --dump (particles) and --dump-bodies (rigid bodies); reports a failed write
// (a full disk) instead of losing data quietly.
class Dump {
public:
    enum class Kind { Particles, RigidBodies };
    Dump(const std::string& path, Kind kind) : path_(path), kind_(kind), file_(std::fopen(path.c_str(), "w")) {
        if (!file_) throw InputError(path + ": cannot write the dump file");
        std::fputs(kind == Kind::Particles ? "tick,time,particle,x,y,z,vx,vy,vz\n"
                                           : "tick,time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz\n",
                   file_);
    }
    ~Dump() {
        if (file_) std::fclose(file_);
    }
    void write(const World& world) {
        if (kind_ == Kind::Particles) {
            // Every soft body's particles, numbered on from one body to the next.
            std::size_t number = 0;
            for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
                const auto& x = world.soft_body(b).x;
                const auto& v = world.soft_body(b).v;
                for (std::size_t i = 0; i < x.size(); ++i, ++number) {
                    std::fprintf(file_, "%" PRIu64 ",%s,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", world.ticks(), tick_time_text(world.ticks(), world.settings().dt).c_str(),
                                 number, x.x[i], x.y[i], x.z[i], v.x[i], v.y[i], v.z[i]);
                }
            }
        } else {
            for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
                const RigidMotion m = world.rigid_motion(b);
                std::fprintf(file_,
                             "%" PRIu64 ",%s,%s,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,"
                             "%.12g,%.12g,%.12g\n",
                             world.ticks(), tick_time_text(world.ticks(), world.settings().dt).c_str(), world.rigid_body(b).name.c_str(), m.x.x, m.x.y, m.x.z, m.q.w, m.q.x,
                             m.q.y, m.q.z, m.v.x, m.v.y, m.v.z, m.omega.x, m.omega.y, m.omega.z, m.L.x, m.L.y, m.L.z);
            }
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
    Kind kind_;
    std::FILE* file_;
};

// --series: the run's time series as CSV (physics/series.h), a row every K ticks from tick 0,
// written as it goes; a failed write is said, not lost quietly.
class SeriesFile {
public:
    SeriesFile(const std::string& path, World& world) : path_(path), series_(world), out_(path, std::ios::binary) {
        if (!out_) throw InputError(path + ": cannot write the series file");
        out_ << series_.csv_header();
        write(world);
    }
    void write(World& world) {
        ledger_.observe(world);  // between two rows nothing from outside changes a simulate run
        series_.record(world, ledger_);
        out_ << series_.csv_row(series_.size() - 1);
        series_.clear();
        if (!out_) throw InputError(path_ + ": writing the series failed");
    }
    void close() {
        out_.close();
        if (!out_) throw InputError(path_ + ": writing the series failed");
    }

private:
    std::string path_;
    EnergyLedger ledger_;
    Series series_;
    std::ofstream out_;
};

}  // namespace

int simulate_command(int argc, char** argv) {
    CLI::App app("Runs the physics alone, without a window or GL, and prints one JSON object: the particles, energy,\n"
                 "centre of mass, lowest point, stability, a hash of the state and every rigid body (app/README.md, \"softbody simulate\").\n"
                 "Notes (a normalised quaternion, a capped particle budget) go to stderr as 'softbody: note: ...'.",
                 "softbody simulate");
    configure(app);
    SceneOptions scene;
    scene.add_to(app);
    std::int64_t ticks = -1;
    double seconds = -1.0;
    std::string dump_path, dump_bodies_path;
    std::int64_t dump_every = 1;
    std::string series_path;
    std::int64_t series_every = 1;
    int threads = kDefaultThreads;
    add_number(app, "--seconds", seconds, 0.0, 1e7, "simulated seconds to run, in whole ticks of dt (this or --ticks is required)")
        ->type_name("T");
    add_whole(app, "--ticks", ticks, 0, 1'000'000'000, "ticks of dt to run (this or --seconds is required)");
    app.add_option("--dump", dump_path,
                   "CSV: tick,time,particle,x,y,z,vx,vy,vz, every soft body, from tick 0 (default: none)")
        ->type_name("FILE.csv");
    app.add_option("--dump-bodies", dump_bodies_path,
                   "CSV: tick,time,body,x,y,z,qw..qz,vx..vz,wx..wz,Lx..Lz, from tick 0 (default: none)")
        ->type_name("FILE.csv");
    add_whole(app, "--dump-every", dump_every, 1, 1'000'000'000, "a dump's row every K ticks (default 1)")->type_name("K");
    app.add_option("--series", series_path,
                   "CSV, a row a tick from tick 0: time, energies, bodies' centres and velocities, springs' lengths and forces (default: none)")
        ->type_name("FILE.csv");
    add_whole(app, "--series-every", series_every, 1, 1'000'000'000, "a series row every K ticks (default 1)")->type_name("K");
    add_whole(app, "--threads", threads, 1, 256, "threads (default " + std::to_string(threads) + "); any count gives the same bits");
    app.footer(exit_codes_help(true));
    if (!parse(app, argc, argv, 2)) return kOk;
    if ((ticks < 0) == (seconds < 0.0)) throw UsageError("give exactly one of --seconds or --ticks");

    const Scene resolved = scene.resolve();
    const WorldSettings& settings = resolved.settings;
    World world(resolved, WorldOptions{threads, false});
    for (const std::string& note : world.notes()) std::cerr << "softbody: note: " << note << "\n";
    if (seconds >= 0.0) ticks = std::llround(seconds / double(settings.dt));

    std::vector<std::unique_ptr<Dump>> dumps;
    if (!dump_path.empty()) dumps.push_back(std::make_unique<Dump>(dump_path, Dump::Kind::Particles));
    if (!dump_bodies_path.empty()) dumps.push_back(std::make_unique<Dump>(dump_bodies_path, Dump::Kind::RigidBodies));
    for (auto& dump : dumps) dump->write(world);
    std::unique_ptr<SeriesFile> series;
    if (!series_path.empty()) series = std::make_unique<SeriesFile>(series_path, world);
    const auto start = std::chrono::steady_clock::now();
    // What the rigid contacts did to the energy (World::contact_energy), over the run and over
    // its last second.
    ContactEnergy contact_work;
    std::deque<double> last_second;
    const std::size_t ticks_a_second = std::max<std::size_t>(1, std::size_t(std::llround(1.0 / double(settings.dt))));
    for (std::int64_t t = 0; t < ticks && world.status() == Status::Ok; ++t) {
        world.tick();
        contact_work.total += world.contact_energy().total;
        contact_work.restitution += world.contact_energy().restitution;
        last_second.push_back(world.contact_energy().total);
        if (last_second.size() > ticks_a_second) last_second.pop_front();
        if (world.status() == Status::Ok && world.ticks() % static_cast<std::uint64_t>(dump_every) == 0) {
            for (auto& dump : dumps) dump->write(world);
        }
        if (series && world.status() == Status::Ok && world.ticks() % static_cast<std::uint64_t>(series_every) == 0) series->write(world);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (auto& dump : dumps) dump->close();
    if (series) series->close();

    const Energy e = world.energy();
    const Stability s = world.stability();
    const Vec3 com = world.center_of_mass();
    const bool ok = world.status() == Status::Ok;
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, world.state_hash());
    std::size_t particles = 0, springs = 0, vertices = 0;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        particles += world.soft_body(b).particle_count();
        springs += world.soft_body(b).spring_count();
        vertices += world.soft_body(b).mesh.vertex_to_particle.size();
    }
    nlohmann::ordered_json out = {
        {"vertices", vertices},
        {"particles", particles},
        {"springs", springs},
        {"ticks", world.ticks()},
        {"sim_time", std::stod(tick_time_text(world.ticks(), world.settings().dt))},  // 1, not 0.99999998
        {"wall_time", wall},
        {"threads", world.threads()},
        {"integrator", to_string(settings.integrator)},
        {"substeps", s.substeps},
        {"energy",
         {{"kinetic", e.kinetic}, {"rotational", e.rotational}, {"gravity", e.gravity}, {"elastic", e.elastic}, {"total", e.total()}}},
        {"contacts_energy",
         {{"total", contact_work.total},
          {"restitution", contact_work.restitution},
          {"last_second", std::accumulate(last_second.begin(), last_second.end(), 0.0)}}},
        {"com", {com.x, com.y, com.z}},
        {"min_z", world.min_z()},
        {"stability", s.h_omega},
        {"stability_limit", s.limit},
        {"stable", s.stable},
        {"substeps_needed", s.substeps_needed},
        {"status", ok ? "ok" : "diverged"},
        {"state_hash", hash},
    };
    if (world.soft_body_count() > 0) out["soft_bodies"] = soft_bodies_json(world);
    if (world.rigid_body_count() > 0) {
        out["sleeping"] = world.sleeping_count();  // rigid bodies asleep at the end (the `sleeping` key)
        out["rigid_bodies"] = rigid_bodies_json(world);
    }
    out["momentum"] = vec_json(world.momentum());
    out["angular_momentum"] = vec_json(world.angular_momentum());
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
