// `softbody simulate` from the outside: each test runs the built executable in a child process
// (posix_spawn, stdout and stderr to files) and checks its exit code, its JSON summary and its
// messages. Meshes and scenes are written to a temporary folder by the tests themselves.
//
// Exit codes: 0 ok, 2 bad input (one line on stderr naming the problem), 3 diverged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using softbody_test::describe;
using softbody_test::read_text;
using softbody_test::Result;
using softbody_test::run;
using softbody_test::TempDir;

// A unit cube centred on the origin, with faces: 8 particles, 28 springs.
const char* kCubeObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// n points in a ball of radius 1.5 m, as an OBJ point cloud.
std::string cloud_obj(int n) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::ostringstream out;
    out.precision(9);
    for (int i = 0; i < n;) {
        const double x = unit(rng), y = unit(rng), z = unit(rng);
        if (x * x + y * y + z * z > 1.0) continue;
        out << "v " << 1.5 * x << " " << 1.5 * y << " " << 1.5 * z << "\n";
        ++i;
    }
    return out.str();
}

// A bad-input run: exit 2, nothing on stdout, and exactly one line on stderr that names the
// problem (each of `names`).
void expect_refused(const std::vector<std::string>& args, std::initializer_list<const char*> names) {
    std::string command;
    for (const auto& arg : args) command += " " + arg;
    SCOPED_TRACE("softbody" + command);
    const Result r = run(args);
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.out, "") << describe(r);
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.back(), '\n') << describe(r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not one line:\n" << r.err;
    for (const char* name : names) EXPECT_NE(r.err.find(name), std::string::npos) << "stderr lacks '" << name << "': " << r.err;
}

// --- The JSON summary ----------------------------------------------------------------------

TEST(Simulate, PrintsOneJsonObjectWithTheSummary) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    const Result r = run({"simulate", "--mesh", mesh, "--ticks", "25", "--threads", "1"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.err, "");
    ASSERT_FALSE(r.out.empty());
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one line: " << r.out;
    const json j = json::parse(r.out);
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j.at("particles"), 8);
    EXPECT_EQ(j.at("springs"), 28);
    EXPECT_EQ(j.at("ticks"), 25);
    EXPECT_NEAR(j.at("sim_time").get<double>(), 25 * 0.02, 1e-6);
    EXPECT_TRUE(j.at("wall_time").is_number());
    EXPECT_GE(j.at("wall_time").get<double>(), 0.0);
    const json& e = j.at("energy");
    for (const char* key : {"kinetic", "gravity", "elastic", "total"}) EXPECT_TRUE(e.at(key).is_number()) << key;
    const double sum = e.at("kinetic").get<double>() + e.at("gravity").get<double>() + e.at("elastic").get<double>();
    EXPECT_NEAR(e.at("total").get<double>(), sum, 1e-9 * std::abs(sum) + 1e-12);
    ASSERT_TRUE(j.at("com").is_array());
    ASSERT_EQ(j.at("com").size(), 3u);
    for (const auto& c : j.at("com")) EXPECT_TRUE(c.is_number());
    EXPECT_TRUE(j.at("min_z").is_number());
    EXPECT_TRUE(j.at("stability").is_number());
    EXPECT_GT(j.at("stability").get<double>(), 0.0);
    EXPECT_EQ(j.at("status"), "ok");
    const std::string hash = j.at("state_hash");
    EXPECT_EQ(hash.size(), 16u);
    EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << hash;
}

// At tick 0 the numbers are known in closed form: the cube (8 kg) rests 2 m up (the default
// init_height) with no motion and no stretch, so its gravitational energy is M g z = 156.96 J.
TEST(Simulate, ZeroTicksReportsTheStartingState) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    const Result r = run({"simulate", "--mesh", mesh, "--ticks", "0", "--set", "init_height=2"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json j = json::parse(r.out);
    EXPECT_EQ(j.at("ticks"), 0);
    EXPECT_EQ(j.at("sim_time").get<double>(), 0.0);
    EXPECT_EQ(j.at("energy").at("kinetic").get<double>(), 0.0);
    EXPECT_EQ(j.at("energy").at("elastic").get<double>(), 0.0);
    // Float positions (2 m, ulp 2.4e-7) times 8 kg and 9.81 m/s^2: 1e-4 J.
    EXPECT_NEAR(j.at("energy").at("gravity").get<double>(), 8 * 9.81 * 2.0, 1e-4);
    EXPECT_NEAR(j.at("com")[2].get<double>(), 2.0, 1e-6);
    EXPECT_NEAR(j.at("min_z").get<double>(), 1.5, 1e-6);
}

TEST(Simulate, SecondsCountTicksOfDt) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    const Result r = run({"simulate", "--mesh", mesh, "--seconds", "0.5", "--set", "dt=0.01"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(json::parse(r.out).at("ticks"), 50);
}

// max_particles=all promises a particle per vertex; above the cap (20,000) the run goes on, on
// at most that many, and one line on stderr says the cap, the particles used and how to ask
// for fewer. The default budget (a number, 3,000) reduces as documented, without a note.
TEST(Simulate, MaxParticlesAllAboveTheCapSaysSoInOneLine) {
    const Result r = run({"simulate", "--mesh", "cloud:20500", "--set", "max_particles=all", "--ticks", "0"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json j = json::parse(r.out);
    EXPECT_EQ(j.at("vertices"), 20500);
    const int particles = j.at("particles");
    EXPECT_LE(particles, 20000);
    EXPECT_EQ(r.err, "softbody: note: cloud:20500: max_particles=all is capped at 20000 particles: its 20500 distinct vertices "
                     "run on " + std::to_string(particles) + " (--set max_particles=N, 4 to 20000, for fewer)\n");
    const Result budget = run({"simulate", "--mesh", "cloud:20500", "--ticks", "0"});
    ASSERT_EQ(budget.exit_code, 0) << describe(budget);
    EXPECT_LE(json::parse(budget.out).at("particles").get<int>(), 3000);
    EXPECT_EQ(budget.err, "");
}

// --- The CSV dump ---------------------------------------------------------------------------

TEST(Simulate, DumpWritesCsvEveryKTicksFromTickZero) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    const std::string csv = dir.file("out.csv");
    const Result r = run({"simulate", "--mesh", mesh, "--ticks", "20", "--dump", csv, "--dump-every", "10",
                          "--threads", "1"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::istringstream lines(read_text(csv));
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line, "tick,time,particle,x,y,z,vx,vy,vz");
    struct Row {
        long tick;
        double time;
        long particle;
        double x, y, z, vx, vy, vz;
    };
    std::vector<Row> rows;
    while (std::getline(lines, line)) {
        Row row{};
        char comma[8];
        std::istringstream in(line);
        in >> row.tick >> comma[0] >> row.time >> comma[1] >> row.particle >> comma[2] >> row.x >> comma[3] >> row.y >>
            comma[4] >> row.z >> comma[5] >> row.vx >> comma[6] >> row.vy >> comma[7] >> row.vz;
        ASSERT_FALSE(in.fail()) << "unreadable row: " << line;
        for (char c : comma) ASSERT_EQ(c, ',') << line;
        rows.push_back(row);
    }
    ASSERT_EQ(rows.size(), 3u * 8u);  // ticks 0, 10 and 20, eight particles each
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const Row& row = rows[k];
        EXPECT_EQ(row.tick, long(k / 8) * 10);
        EXPECT_NEAR(row.time, double(row.tick) * 0.02, 1e-6);
        EXPECT_EQ(row.particle, long(k % 8));
    }
    // Tick 0 is the start: the cube's corners lifted by init_height, at rest.
    for (std::size_t k = 0; k < 8; ++k) {
        EXPECT_EQ(std::abs(rows[k].x), 0.5);
        EXPECT_EQ(std::abs(rows[k].y), 0.5);
        EXPECT_NEAR(rows[k].z, rows[k].z > 2.0 ? 2.5 : 1.5, 1e-6);
        EXPECT_EQ(rows[k].vx, 0.0);
        EXPECT_EQ(rows[k].vz, 0.0);
    }
    // The last rows are the final state that the summary describes.
    const json j = json::parse(r.out);
    double com_z = 0.0;
    for (std::size_t k = 16; k < 24; ++k) com_z += rows[k].z / 8.0;
    EXPECT_NEAR(com_z, j.at("com")[2].get<double>(), 1e-6);  // %.9g in the CSV
}

// --- Rigid bodies ---------------------------------------------------------------------------

// A box thrown spinning into empty space (no gravity, no ground): its summary entry has every
// field of the contract, and they agree with the closed form of free flight.
const char* kThrownBox =
    "{\"gravity\": [0, 0, 0], \"ground\": false, \"rigid_bodies\": [{\"name\": \"crate\", \"shape\": \"box\","
    " \"size\": [1, 2, 3], \"mass\": 6, \"position\": [0, 0, 1], \"velocity\": [1, 0, 0], \"angular_velocity\": [0, 0, 2]}]}";

TEST(Simulate, RigidBodiesAreReportedWithMomentumAndInertia) {
    TempDir dir;
    const std::string scene = dir.write("box.json", kThrownBox);
    const Result r = run({"simulate", "--scene", scene, "--ticks", "50"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json j = json::parse(r.out);
    EXPECT_EQ(j.at("particles"), 0);  // no "mesh": no soft body
    ASSERT_EQ(j.at("rigid_bodies").size(), 1u);
    const json& b = j.at("rigid_bodies")[0];
    for (const char* key : {"name", "mass", "position", "orientation", "velocity", "angular_velocity", "angular_momentum",
                            "inertia", "kinetic_energy"}) {
        EXPECT_TRUE(b.contains(key)) << key;
    }
    EXPECT_EQ(b.at("name"), "crate");
    EXPECT_EQ(b.at("mass"), 6.0);
    // One second at 1 m/s along x (symplectic Euler is exact for constant velocity), turning
    // about its own z axis, a principal axis: w stays (0, 0, 2) and q = (cos 1, 0, 0, sin 1).
    EXPECT_NEAR(b.at("position")[0].get<double>(), 50 * double(0.02f), 1e-12);
    EXPECT_NEAR(b.at("angular_velocity")[2].get<double>(), 2.0, 1e-12);
    EXPECT_NEAR(b.at("orientation")[0].get<double>(), std::cos(50 * double(0.02f)), 1e-9);
    EXPECT_NEAR(b.at("orientation")[3].get<double>(), std::sin(50 * double(0.02f)), 1e-9);
    // J in world axes (Eq. 32), 3x3 rows: about z it is m (a^2 + b^2) / 12 = 2.5 whatever the turn.
    EXPECT_EQ(b.at("inertia").size(), 3u);
    EXPECT_NEAR(b.at("inertia")[2][2].get<double>(), 6.0 * (1.0 + 4.0) / 12.0, 1e-12);
    EXPECT_NEAR(b.at("angular_momentum")[2].get<double>(), 2.5 * 2.0, 1e-12);
    // 1/2 m v^2 + 1/2 J w^2 = 3 + 5.
    EXPECT_NEAR(b.at("kinetic_energy").get<double>(), 3.0 + 5.0, 1e-9);
    // World totals about the origin: P = m v; L = x x P + L_spin, with x x P = (0, 0, 1) x (6, 0, 0) = (0, 6, 0).
    EXPECT_NEAR(j.at("momentum")[0].get<double>(), 6.0, 1e-12);
    EXPECT_NEAR(j.at("angular_momentum")[1].get<double>(), 6.0, 1e-12);
    EXPECT_NEAR(j.at("angular_momentum")[2].get<double>(), 5.0, 1e-12);
}

// min_z is the lowest point of any body's shape: boxes and balls settled in their bin (all 30
// asleep by 10 s; the last fall asleep at 6 to 7 s) report the ground (to the millimetre the
// contacts let bodies sink), not the walls' bounding spheres (-0.63 m), and a box turned 45
// degrees about x its lowest edge, 2 - sqrt(1/2) m.
TEST(Simulate, MinZIsTheLowestPointOfAnyBodysShape) {
    const Result pile = run({"simulate", "--scene", "boxes:30", "--seconds", "10"});
    ASSERT_EQ(pile.exit_code, 0) << describe(pile);
    ASSERT_EQ(json::parse(pile.out).at("sleeping").get<int>(), 30);
    EXPECT_NEAR(json::parse(pile.out).at("min_z").get<double>(), 0.0, 1e-3);
    TempDir dir;
    const std::string scene = dir.write("tilted.json", "{\"gravity\": [0, 0, 0], \"rigid_bodies\": [{\"name\": \"cube\", "
                                                       "\"shape\": \"box\", \"size\": [1, 1, 1], \"position\": [0, 0, 2], "
                                                       "\"rotation\": [45, 0, 0]}]}");
    const Result tilted = run({"simulate", "--scene", scene, "--ticks", "0"});
    ASSERT_EQ(tilted.exit_code, 0) << describe(tilted);
    EXPECT_NEAR(json::parse(tilted.out).at("min_z").get<double>(), 2.0 - std::sqrt(0.5), 1e-6);
}

TEST(Simulate, DumpBodiesWritesEveryRigidBodyEveryKTicks) {
    TempDir dir;
    const std::string scene = dir.write("box.json", kThrownBox);
    const std::string csv = dir.file("bodies.csv");
    const Result r = run({"simulate", "--scene", scene, "--ticks", "20", "--dump-bodies", csv, "--dump-every", "10"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::istringstream lines(read_text(csv));
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line, "tick,time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz");
    std::vector<std::string> rows;
    while (std::getline(lines, line)) rows.push_back(line);
    ASSERT_EQ(rows.size(), 3u);  // ticks 0, 10, 20
    EXPECT_EQ(rows[0].rfind("0,0,crate,0,0,1,1,0,0,0,1,0,0,0,0,2,", 0), 0u) << rows[0];
    EXPECT_EQ(rows[2].rfind("20,", 0), 0u) << rows[2];
    EXPECT_EQ(std::count(rows[2].begin(), rows[2].end(), ','), 18);
}

TEST(Simulate, SetByBodyNameChangesThatBody) {
    TempDir dir;
    const std::string scene = dir.write("box.json", kThrownBox);
    const Result r = run({"simulate", "--scene", scene, "--ticks", "1", "--set", "crate.mass=3"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(json::parse(r.out).at("rigid_bodies")[0].at("mass"), 3.0);
    expect_refused({"simulate", "--scene", scene, "--ticks", "1", "--set", "crate.mass=-3"}, {"'crate'", "'mass'"});
    expect_refused({"simulate", "--scene", scene, "--ticks", "1", "--set", "cart.mass=3"}, {"'cart'", "crate"});
}

TEST(BadInput, BadRigidBodyNamesBodyAndKey) {
    TempDir dir;
    expect_refused({"simulate", "--scene", dir.write("a.json", "{\"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0}]}"),
                    "--ticks", "1"},
                   {"a.json:1", "'ball'", "'radius'"});
    expect_refused({"simulate", "--scene", dir.write("b.json", "{\"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"blob\"}]}"),
                    "--ticks", "1"},
                   {"'ball'", "'shape'", "blob"});
    expect_refused({"simulate", "--scene", dir.write("c.json", "{\"ground\": true}"), "--ticks", "1"}, {"nothing to simulate"});
}

// --- Bad input: exit 2, one line on stderr -------------------------------------------------

TEST(BadInput, UnknownOption) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--frobnicate"}, {"--frobnicate"});
}

TEST(BadInput, MissingValue) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh, "--ticks"}, {"--ticks"});
    expect_refused({"simulate", "--ticks", "5", "--mesh"}, {"--mesh"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set"}, {"--set"});
}

TEST(BadInput, BadValues) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "-5"}, {"--ticks"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "ten"}, {"--ticks"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--threads", "0"}, {"--threads"});
}

TEST(BadInput, BadSet) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "stiffness"}, {"--set", "stiffness"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "=3"}, {"--set"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "stiffness=abc"}, {"'stiffness'"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "dt=0"}, {"'dt'"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "particle_mass=-1"}, {"'particle_mass'"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "substeps=0"}, {"'substeps'"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "static_friction=nan"}, {"'static_friction'"});
}

TEST(BadInput, UnknownKey) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--set", "stifness=3"}, {"'stifness'", "'stiffness'"});
    const std::string scene = dir.write("scene.json", "{\n  \"mesh\": \"cube.obj\",\n  \"wobble\": 1\n}\n");
    expect_refused({"simulate", "--scene", scene, "--ticks", "5"}, {"scene.json:3", "'wobble'"});
}

TEST(BadInput, MissingMeshFile) {
    TempDir dir;
    const std::string absent = dir.file("absent.obj");
    expect_refused({"simulate", "--mesh", absent, "--ticks", "5"}, {absent.c_str()});
    expect_refused({"simulate", "--scene", dir.file("absent.json"), "--ticks", "5"}, {"absent.json"});
}

TEST(BadInput, MalformedMeshNamesFileAndLine) {
    TempDir dir;
    const std::string obj = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    expect_refused({"simulate", "--mesh", obj, "--ticks", "5"}, {"bad.obj:3:"});
    const std::string faces = dir.write("faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    expect_refused({"simulate", "--mesh", faces, "--ticks", "5"}, {"faces.obj:4:"});
    const std::string off = dir.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
    expect_refused({"simulate", "--mesh", off, "--ticks", "5"}, {"bad.off:"});
}

TEST(BadInput, BothOrNeitherOfSecondsAndTicks) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    expect_refused({"simulate", "--mesh", mesh}, {"--seconds", "--ticks"});
    expect_refused({"simulate", "--mesh", mesh, "--ticks", "5", "--seconds", "1"}, {"--seconds", "--ticks"});
}

// --- Divergence: exit 3, with what to change ------------------------------------------------

TEST(Simulate, DivergingRunExitsWithThreeAndSaysWhatToChange) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", kCubeObj);
    // k = 1e5 N/m on 8 particles, one step a tick: N k h^2 = 320, far past the limit of 4 m; the
    // landing sets it off.
    const Result r = run({"simulate", "--mesh", mesh, "--ticks", "500", "--set", "stiffness=100000", "--set",
                          "auto_substeps=false", "--threads", "1"});
    EXPECT_EQ(r.exit_code, 3) << describe(r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not one line:\n" << r.err;
    EXPECT_NE(r.err.find("substeps"), std::string::npos) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j.at("status"), "diverged");
    EXPECT_LT(j.at("ticks").get<int>(), 500);
    // The last finite state is reported: every number in the summary is finite (JSON has no
    // NaN; nlohmann writes a non-finite number as null).
    EXPECT_TRUE(j.at("energy").at("total").is_number());
    for (const auto& c : j.at("com")) EXPECT_TRUE(c.is_number());
}

// What the contacts did to the energy: a 2 kg ball dropped 1 m onto the ground with e = 0.5
// (RK4, whose free flight is exact): over its first bounce the contacts take 1 - e^2 of the
// 19.62 J it met the ground with (m g h), and the bounce gives back e^2 of it (to 1%).
TEST(Simulate, ContactsEnergySaysWhatABounceTook) {
    TempDir dir;
    const std::string scene = dir.write(
        "ball.json", "{\"restitution\": 0.5, \"integrator\": \"rk4\", \"rigid_bodies\": [{\"name\": \"ball\","
                     " \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 2, \"position\": [0, 0, 1.1]}]}");
    const Result r = run({"simulate", "--scene", scene, "--ticks", "40"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json e = json::parse(r.out).at("contacts_energy");
    const double met = 2.0 * 9.81 * 1.0;
    EXPECT_NEAR(e.at("total").get<double>(), -0.75 * met, 0.01 * met);
    EXPECT_NEAR(e.at("restitution").get<double>(), 0.25 * met, 0.01 * met);
    EXPECT_NEAR(e.at("last_second").get<double>(), e.at("total").get<double>(), 1e-9);  // 40 ticks < 1 s
}

// Sleeping: the summary says how many rigid bodies sleep at the end (and each body whether it
// does). The bundled pyramid sleeps whole within 2 s; with the key off, none does; and a bad
// value is refused in one line.
TEST(Simulate, SleepingBodiesAreCountedAndTheKeyTurnsItOff) {
    const std::string pyramid = std::string(SOFTBODY_ASSETS) + "/scenes/pyramid.json";
    const Result on = run({"simulate", "--scene", pyramid, "--seconds", "2"});
    ASSERT_EQ(on.exit_code, 0) << describe(on);
    const json j = json::parse(on.out);
    EXPECT_EQ(j.at("sleeping"), 385);
    EXPECT_EQ(j.at("rigid_bodies").size(), 385u);
    EXPECT_EQ(j.at("rigid_bodies")[384].at("asleep"), true);
    const Result off = run({"simulate", "--scene", "boxes:20", "--seconds", "3", "--set", "sleeping=false"});
    ASSERT_EQ(off.exit_code, 0) << describe(off);
    EXPECT_EQ(json::parse(off.out).at("sleeping"), 0);
    const Result pile = run({"simulate", "--scene", "boxes:20", "--seconds", "3"});
    ASSERT_EQ(pile.exit_code, 0) << describe(pile);
    EXPECT_GT(json::parse(pile.out).at("sleeping").get<int>(), 0);
    expect_refused({"simulate", "--scene", "boxes:20", "--ticks", "1", "--set", "sleeping=sometimes"}, {"sleeping"});
}

// Explicit Euler gains energy in free rotation (Listing 9): on random scenes it may diverge, and
// then it says so in one line with exit 3 and a summary of the last good state; never a crash.
TEST(Simulate, ExplicitEulerOnRandomScenesRunsOrStopsInOneLine) {
    int diverged = 0;
    for (int seed = 1; seed <= 12; ++seed) {
        const Result r = run({"simulate", "--scene", "random:" + std::to_string(seed), "--set", "integrator=explicit_euler",
                              "--seconds", "5", "--threads", "1"});
        ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << describe(r);
        const json j = json::parse(r.out);
        EXPECT_TRUE(j.at("energy").at("total").is_number());
        if (r.exit_code == 3) {
            ++diverged;
            EXPECT_EQ(j.at("status"), "diverged");
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not one line:\n" << r.err;
        }
    }
    std::printf("explicit Euler: %d of 12 random scenes diverged\n", diverged);
}

// --- Threads ----------------------------------------------------------------------------------

// 550 particles are three blocks of the pair kernel (256 each): the threads share six tiles and
// each particle's force sums three partials, yet the bits must not depend on the thread count.
TEST(Simulate, SameStateHashAtOneAndTwoThreads) {
    TempDir dir;
    const std::string mesh = dir.write("cloud.obj", cloud_obj(550));
    // Half of Listing 8's stiffness keeps 550 particles within the stability limit at one substep.
    const std::vector<std::string> base{"simulate", "--mesh", mesh, "--ticks", "60", "--set", "stiffness=5"};
    std::vector<std::string> one = base, two = base;
    one.insert(one.end(), {"--threads", "1"});
    two.insert(two.end(), {"--threads", "2"});
    const Result a = run(one), b = run(two), again = run(one);
    ASSERT_EQ(a.exit_code, 0) << describe(a);
    ASSERT_EQ(b.exit_code, 0) << describe(b);
    const json ja = json::parse(a.out), jb = json::parse(b.out);
    EXPECT_EQ(ja.at("particles"), 550);
    EXPECT_EQ(ja.at("state_hash"), jb.at("state_hash"));
    EXPECT_EQ(ja.at("state_hash"), json::parse(again.out).at("state_hash"));
}

// --- Help -------------------------------------------------------------------------------------

// The options of a command's --help: each line of an options section (a line starting "  -"),
// split into the option with its value's name and what it says.
struct HelpLine {
    std::string option, text;
};
std::vector<HelpLine> option_lines(const std::string& help, std::vector<std::string>& loose) {
    std::vector<HelpLine> lines;
    std::istringstream in(help);
    std::string line;
    bool in_options = false;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        if (line.back() == ':' && line[0] != ' ') {  // a section's title: "Options:", "Camera and look:"
            in_options = line.rfind("Exit codes", 0) != 0;
            continue;
        }
        if (!in_options) continue;
        if (line.rfind("  -", 0) != 0) {
            loose.push_back(line);  // a line that is no option's: a description run onto its own line
            continue;
        }
        const auto gap = line.find("  ", 2);
        const auto text = gap == std::string::npos ? std::string::npos : line.find_first_not_of(' ', gap);
        lines.push_back({line.substr(2, gap == std::string::npos ? std::string::npos : gap - 2),
                         text == std::string::npos ? "" : line.substr(text)});
    }
    return lines;
}

// Every command's --help: exit 0, each option on one line of its own saying what it does, and
// each option that takes a value its default (or that it is required); the exit codes.
TEST(Help, EveryCommandGivesEachOptionOneLineWithItsDefault) {
    for (const std::string command : {"simulate", "render", "bench", "lessons"}) {
        SCOPED_TRACE("softbody " + command + " --help");
        const Result r = run({command, "--help"});
        if (command == "render" && r.exit_code == 2 && r.err.find("without the renderer") != std::string::npos) continue;
        ASSERT_EQ(r.exit_code, 0) << describe(r);
        EXPECT_EQ(r.err, "");
        EXPECT_EQ(r.out.rfind("Usage: softbody " + command + " [OPTIONS]"), r.out.find("Usage:")) << r.out;
        std::vector<std::string> loose;
        const std::vector<HelpLine> options = option_lines(r.out, loose);
        EXPECT_GE(options.size(), 2u) << r.out;
        EXPECT_TRUE(loose.empty()) << "not on its option's line: " << (loose.empty() ? "" : loose[0]);
        for (const HelpLine& o : options) {
            EXPECT_GE(o.text.size(), 8u) << "says nothing: " << o.option;
            const bool takes_value = o.option.find(' ') != std::string::npos && o.option.rfind("-h,", 0) != 0;
            if (takes_value) {
                EXPECT_TRUE(o.text.find("default") != std::string::npos || o.text.find("required") != std::string::npos)
                    << o.option << ": no default in '" << o.text << "'";
            }
        }
        EXPECT_NE(r.out.find("Exit codes:\n  0  done\n  2  bad input"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("\n  4  "), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("\n  3  ") != std::string::npos, command == "simulate" || command == "render") << r.out;
    }
}

// simulate's help says what the options the issue asked about do: what --dump writes, the
// thread count it defaults to, and the exit codes 0, 2, 3 and 4.
TEST(Help, SimulateSaysWhatDumpWritesTheThreadsAndTheExitCodes) {
    const Result r = run({"simulate", "--help"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::vector<std::string> loose;
    std::map<std::string, std::string> text;
    for (const HelpLine& o : option_lines(r.out, loose)) text[o.option.substr(0, o.option.find(' '))] = o.text;
    for (const char* option : {"--scene", "--mesh", "--set", "--seconds", "--ticks", "--dump", "--dump-bodies", "--dump-every",
                               "--threads"}) {
        EXPECT_TRUE(text.count(option)) << option << " is not listed:\n" << r.out;
    }
    EXPECT_NE(text["--dump"].find("tick,time,particle,x,y,z,vx,vy,vz"), std::string::npos) << text["--dump"];
    EXPECT_NE(text["--dump-bodies"].find("tick,time,body,x,y,z"), std::string::npos) << text["--dump-bodies"];
    const auto at = text["--threads"].find("default ");
    ASSERT_NE(at, std::string::npos) << text["--threads"];
    EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(text["--threads"][at + 8]))) << text["--threads"];
    for (const char* code : {"\n  0  done", "\n  2  bad input", "\n  3  the simulation diverged", "\n  4  "}) {
        EXPECT_NE(r.out.find(code), std::string::npos) << code << "\n" << r.out;
    }
}

}  // namespace

// `softbody lessons`: the lessons in the addendum's order, in text and as JSON, each with its
// number, title, scene file, equations and text; lessons with a closed form say which.
TEST(Lessons, ListsTheLessonsInOrder) {
    const Result text = run({"lessons"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_EQ(text.out.rfind(" 1. A single spring  (spring.json, Eq. 21)\n", 0), 0u) << text.out;
    EXPECT_NE(text.out.find("11. Figure 7's collision  (figure7.json, Eq. 37, 38, Figure 7)"), std::string::npos) << text.out;

    const Result listed = run({"lessons", "--json"});
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    const json out = json::parse(listed.out);
    const std::vector<std::string> files = {"spring.json", "damper.json", "drag.json", "slope.json",
                                            "listing8.json", "stability.json", "seesaw.json", "tumbling_box.json",
                                            "quaternion.json", "intermediate_axis.json", "figure7.json", "collision_1d.json",
                                            "springs_parallel.json", "springs_series.json"};
    ASSERT_EQ(out["lessons"].size(), files.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        const json& lesson = out["lessons"][i];
        EXPECT_EQ(lesson["number"], i + 1);
        EXPECT_EQ(lesson["scene"], files[i]);
        EXPECT_FALSE(lesson["title"].get<std::string>().empty());
        EXPECT_NE(lesson["text"].get<std::string>().find("Try:"), std::string::npos) << files[i];
        EXPECT_NE(text.out.find(lesson["title"].get<std::string>() + "  (" + files[i]), std::string::npos) << files[i];
    }
    EXPECT_EQ(out["lessons"][0]["expect"]["kind"], "spring_period");
    EXPECT_EQ(out["lessons"][2]["expect"]["kind"], "terminal_velocity");
    EXPECT_EQ(out["lessons"][3]["expect"]["kind"], "friction_slope");
    EXPECT_EQ(out["lessons"][9]["expect"]["kind"], "flip_period");
    EXPECT_FALSE(out["lessons"][6].contains("expect"));  // the seesaw has no closed form

    const Result bad = run({"lessons", "--verbose"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// A bad "title" or "expect" in a scene: one line naming the file, the line and the key; exit 2.
TEST(BadInput, BadLessonKeysNameFileLineAndKey) {
    TempDir dir;
    const std::string scene = dir.write("lesson.json",
                                        "{\n  \"title\": \"A ball\",\n  \"expect\": {\"kind\": \"period\", \"body\": \"ball\"},\n"
                                        "  \"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.1}]\n}\n");
    const Result r = run({"simulate", "--scene", scene, "--ticks", "1"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("lesson.json:3: key 'expect': unknown kind 'period'"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// --- softbody bench: rigid bodies at scale --------------------------------------------------
// Speed is never asserted; these check that the section runs, says what it measured and is
// sound on a short drop. They pass with or without the Bullet peer built beside softbody.

TEST(Bench, ScaleOnlyPrintsTheSectionAndSoftbodysRows) {
    const Result r = run({"bench", "--scale-only", "--scale-scenes", "boxes:100", "--scale-seconds", "0.2", "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_NE(r.out.find("rigid bodies at scale"), std::string::npos) << r.out;
    // One row per thread count, as it was measured, and the side-by-side table.
    EXPECT_NE(r.out.find("boxes:100                 softbody, 1 thread "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("boxes:100                 softbody, 2 threads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| `boxes:100` | 100 | 0.2 |"), std::string::npos) << r.out;
    // Either the peer ran, or the section says how to get it.
    const bool peer = r.out.find("Bullet runs:") != std::string::npos;
    const bool skipped = r.out.find("Bullet comparison skipped") != std::string::npos &&
                         r.out.find("sudo apt install libbullet-dev") != std::string::npos;
    EXPECT_TRUE(peer != skipped) << r.out;
    // --scale-only: nothing of the clouds, kernels or memory.
    EXPECT_EQ(r.out.find("pair kernel alone"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("memory the pair forces need"), std::string::npos) << r.out;
}

TEST(Bench, ScaleJsonGivesSoundnessFiguresOfAShortDrop) {
    // 0.2 s after boxes:100 is let go nothing has landed (the lowest layer starts 0.7 m up and
    // falls 0.2 m): every body moves, none is in the ground, and the energy is the fall's.
    const Result r = run({"bench", "--scale-only", "--scale-scenes", "boxes:100", "--scale-seconds", "0.2", "--threads", "2",
                          "--no-peer", "--json"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json j = json::parse(r.out);
    const json& rows = j.at("scale").at("rows");
    ASSERT_EQ(rows.size(), 2u) << r.out;
    for (const json& row : rows) {
        EXPECT_EQ(row.at("engine"), "softbody");
        EXPECT_EQ(row.at("status"), "ok");
        EXPECT_EQ(row.at("bodies"), 100);
        EXPECT_EQ(row.at("ticks"), 10);
        EXPECT_EQ(row.at("moving"), 100);
        EXPECT_EQ(row.at("penetration_m").get<double>(), 0.0);
        EXPECT_GT(row.at("kinetic_J").get<double>(), 0.0);
        EXPECT_TRUE(row.at("top_moved_m").is_null());
        EXPECT_GT(row.at("ms_per_tick").get<double>(), 0.0);
    }
    EXPECT_EQ(rows[0].at("threads"), 1);
    EXPECT_EQ(rows[1].at("threads"), 2);
    // The same world at either thread count: the same energy to the bit.
    EXPECT_EQ(rows[0].at("kinetic_J").get<double>(), rows[1].at("kinetic_J").get<double>());
}

TEST(Bench, ScaleSceneWithAKeyRunsThatVariant) {
    // A 4-layer pyramid is asleep within a second; the same with sleeping off is not, and it
    // still stands (nothing moves): the key reached the run, and the row keeps its full name.
    const Result r = run({"bench", "--scale-only", "--scale-scenes", "pyramid:4,pyramid:4@sleeping=false", "--scale-seconds", "1",
                          "--threads", "1", "--no-peer", "--json"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json rows = json::parse(r.out).at("scale").at("rows");
    ASSERT_EQ(rows.size(), 2u) << r.out;
    EXPECT_EQ(rows[0].at("scene"), "pyramid:4");
    EXPECT_EQ(rows[0].at("sleeping"), 30);
    EXPECT_EQ(rows[1].at("scene"), "pyramid:4@sleeping=false");
    EXPECT_EQ(rows[1].at("sleeping"), 0);
    EXPECT_EQ(rows[1].at("moving"), 0);
}

// --- softbody bench: a busy machine ----------------------------------------------------------
// The section spins a process on one core for the length of its runs (a few ticks here). Its
// times are never checked: only that it ran each scene at both thread counts, with the same
// answer at each.

TEST(Bench, BusyOnlyRunsEachSceneAtOneAndTwoThreadsWithTheSameState) {
    const Result r = run({"bench", "--busy-only", "--busy-scenes", "pile:100+cloud:300,ball:3 on pyramid:3", "--busy-ticks", "3",
                          "--busy-repeats", "2", "--threads", "2", "--json"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const json j = json::parse(r.out);
    EXPECT_FALSE(j.contains("rows")) << r.out;   // nothing of the clouds
    EXPECT_FALSE(j.contains("scale")) << r.out;  // nor of the rigid bodies at scale
    const json& busy = j.at("busy");
    EXPECT_EQ(busy.at("threads"), 2);
    EXPECT_EQ(busy.at("repeats"), 2);
    const json& rows = busy.at("rows");
    ASSERT_EQ(rows.size(), 2u) << r.out;
    EXPECT_EQ(rows[0].at("scene"), "pile:100+cloud:300");
    EXPECT_EQ(rows[1].at("scene"), "ball:3 on pyramid:3");
    for (const json& row : rows) {
        EXPECT_EQ(row.at("status"), "ok") << row.dump();
        EXPECT_EQ(row.at("ticks"), 3);
        EXPECT_EQ(row.at("runs_1_thread").size(), 2u);
        EXPECT_EQ(row.at("runs_threads").size(), 2u);
        EXPECT_GT(row.at("seconds_1_thread").get<double>(), 0.0);
        EXPECT_GT(row.at("seconds_threads").get<double>(), 0.0);
        EXPECT_DOUBLE_EQ(row.at("ratio").get<double>(),
                         row.at("seconds_threads").get<double>() / row.at("seconds_1_thread").get<double>());
        EXPECT_TRUE(row.at("same_state_hash").get<bool>()) << row.dump();
    }
}

TEST(Bench, BusyOnlyPrintsTheSectionAlone) {
    const Result r = run({"bench", "--busy-only", "--busy-scenes", "soft_stack.json", "--busy-ticks", "2", "--busy-repeats", "1",
                          "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_NE(r.out.find("busy machine: another process spins on one core"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("soft_stack.json"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ratio"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("rigid bodies at scale"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("pair kernel alone"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("memory the pair forces need"), std::string::npos) << r.out;
}

TEST(BadInput, BenchBusyOptionsAreRefusedInOneLine) {
    expect_refused({"bench", "--busy-only", "--no-busy"}, {"--busy-only", "--no-busy"});
    expect_refused({"bench", "--busy-only", "--scale-only"}, {"--busy-only", "--scale-only"});
    expect_refused({"bench", "--busy-only", "--busy-scenes", "pile:lots"}, {"pile:lots"});
    expect_refused({"bench", "--busy-only", "--busy-scenes", "pile:100,"}, {"empty"});
    expect_refused({"bench", "--busy-ticks", "0"}, {"--busy-ticks"});
}

TEST(BadInput, BenchScaleOptionsAreRefusedInOneLine) {
    expect_refused({"bench", "--scale-only", "--scale-scenes", "cloud:100"}, {"--scale-scenes", "cloud:100", "no rigid bodies"});
    expect_refused({"bench", "--scale-only", "--scale-scenes", "boxes:100,"}, {"--scale-scenes", "empty"});
    expect_refused({"bench", "--scale-only", "--scale-scenes", "boxes:lots"}, {"boxes:lots"});
    expect_refused({"bench", "--scale-only", "--scale-scenes", "boxes:100@sleeping"}, {"--scale-scenes", "NAME@KEY=VALUE"});
    expect_refused({"bench", "--scale-only", "--scale-scenes", "boxes:100@nokey=1"}, {"--scale-scenes", "boxes:100@nokey=1", "nokey"});
    expect_refused({"bench", "--scale-only", "--no-scale"}, {"--scale-only", "--no-scale"});
    expect_refused({"bench", "--scale-seconds", "0"}, {"--scale-seconds"});
}
