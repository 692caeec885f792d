// The desktop app as a user drives it, replayed from scripts: it starts and shows the scene,
// a drag moves the body, a preset is saved and loaded back without overwriting anything, and
// bad input shows an error instead of ending the app.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <string>

#include "physics/lesson.h"
#include "render/image.h"

namespace fs = std::filesystem;

namespace {

struct Result {
    int exit_code = -1;
    std::string out, err;
    nlohmann::json summary;  // the JSON line the app prints when it ends
};

fs::path scratch() {
    const fs::path dir = fs::temp_directory_path() / ("softbody_app_tests_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

// Runs `softbody run ...` in a window: under a virtual display when there is no display.
// From `folder` when given (scripts whose paths are relative to the repository).
Result run_app(const std::string& arguments, const fs::path& folder = {}) {
    const fs::path err_file = scratch() / "stderr.txt";
    std::string command;
    if (!folder.empty()) command = "cd " + quote(folder.string()) + " && ";
    if (!std::getenv("DISPLAY")) command += "xvfb-run -a -s '-screen 0 1280x800x24' ";
    command += std::string(SOFTBODY_EXE) + " run " + arguments + " 2>" + quote(err_file.string());
    Result result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    while (std::fgets(buffer.data(), buffer.size(), pipe)) result.out += buffer.data();
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(err_file);
    result.err.assign(std::istreambuf_iterator<char>(err), {});
    std::string text = result.out;
    while (!text.empty() && text.back() == '\n') text.pop_back();
    const auto last_line = text.rfind('\n');
    result.summary = nlohmann::json::parse(last_line == std::string::npos ? text : text.substr(last_line + 1), nullptr, false);
    if (result.summary.is_discarded()) result.summary = nlohmann::json::object();
    return result;
}

fs::path write_script(const std::string& name, const std::string& text) {
    const fs::path path = scratch() / name;
    std::ofstream(path) << text;
    return path;
}

double com_z(const Result& r) { return r.summary["com"][2].get<double>(); }

}  // namespace

TEST(App, StartsAndShowsTheSceneAndPanels) {
    const fs::path shot = scratch() / "start.png";
    const Result r = run_app("--size 800x600 --frames 30 --screenshot " + quote(shot.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.summary["status"], "ok");
    EXPECT_EQ(r.summary["particles"], 162);  // the default scene's sphere
    EXPECT_EQ(r.summary["ticks"], 25);       // 30 frames of 1/60 s at a 0.02 s tick
    const auto image = softbody::render::read_png(shot.string());
    ASSERT_EQ(image.width, 800);
    ASSERT_EQ(image.height, 600);
    // The panel (dark) on the left and the scene (light ground and sky) on the right.
    auto brightness = [&](int x, int y) {
        const auto* p = image.pixel(x, y);
        return (p[0] + p[1] + p[2]) / 3;
    };
    // (in the panel's margin, left of its contents: a plot's line may cross any point inside)
    EXPECT_LT(brightness(12, 580), 80) << "no panel drawn at the bottom left";
    EXPECT_GT(brightness(780, 20), 150) << "no sky at the top right";
}

// The default ball, left alone, rolls 2.5 m from where it fell; the camera follows it (on by
// default for a scene with one body): after 30 s its target has moved as the ball's centre did,
// level, to the smoothing's lag (0.4 s behind a ball all but at rest), so the ball stays where
// the first framing put it in the view. With T pressed at the start the camera stays put, and
// a scene of several bodies starts without following.
TEST(App, CameraFollowsTheDefaultBall) {
    const std::string common = "--size 480x300 --frames 600 --frame-time 0.05";  // 30 s
    const Result followed = run_app(common);
    const Result stayed = run_app(common + " --script " + quote(write_script("follow_off.script", "0 key t\n").string()));
    ASSERT_EQ(followed.exit_code, 0) << followed.err;
    ASSERT_EQ(stayed.exit_code, 0) << stayed.err;
    EXPECT_TRUE(followed.summary["camera"]["follow"].get<bool>());
    EXPECT_FALSE(stayed.summary["camera"]["follow"].get<bool>());
    // The same run either way (the camera does not touch the physics): the ball rolled away.
    EXPECT_EQ(followed.summary["state_hash"], stayed.summary["state_hash"]);
    const auto& com = followed.summary["com"];
    const double rolled = std::hypot(com[0].get<double>(), com[1].get<double>());  // it fell at x = y = 0
    EXPECT_GT(rolled, 1.5) << followed.out;
    // The camera that stayed is where the framing put it at the start: the follow moved the
    // other by the ball's way, and not up or down.
    const auto& moved = followed.summary["camera"]["target"];
    const auto& start = stayed.summary["camera"]["target"];
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(moved[k].get<double>() - start[k].get<double>(), com[k].get<double>(), 0.05) << "axis " << k;
    }
    EXPECT_EQ(moved[2].get<double>(), start[2].get<double>());

    const Result pile = run_app("--scene pile:5 --size 480x300 --frames 2");
    ASSERT_EQ(pile.exit_code, 0) << pile.err;
    EXPECT_FALSE(pile.summary["camera"]["follow"].get<bool>());
}

// `softbody run --help` lists its options, the mouse and every key, each with what it does (the
// same list the help overlay shows: gui/bindings.cpp), and opens no window.
TEST(App, RunHelpListsTheOptionsTheMouseAndEveryKey) {
    FILE* pipe = ::popen((std::string(SOFTBODY_EXE) + " run --help 2>&1").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string help;
    std::array<char, 4096> buffer;
    while (std::fgets(buffer.data(), buffer.size(), pipe)) help += buffer.data();
    const int status = ::pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << help;
    for (const char* option : {"--scene FILE", "--mesh FILE", "--set KEY=VALUE", "--size WxH", "--frames N", "--frame-time S",
                               "--script FILE", "--screenshot FILE.png"}) {
        EXPECT_NE(help.find("\n  " + std::string(option) + " "), std::string::npos) << option << " missing:\n" << help;
    }
    const auto mouse = help.find("\nMouse"), keys = help.find("\nKeys:\n");
    ASSERT_NE(mouse, std::string::npos) << help;
    ASSERT_NE(keys, std::string::npos) << help;
    for (const char* gesture : {"left-drag on a body", "shift + left-click", "ctrl + left-click", "right-drag", "middle-drag", "wheel",
                                "drop a file"}) {
        EXPECT_NE(help.find(gesture, mouse), std::string::npos) << gesture << " missing:\n" << help;
    }
    // Every key the controls act on, each on its own line with what it does.
    for (const char* key : {"Space", "N or .", ", (comma)", "R", "F", "T", "P", "S", "C", "V", "W", "M", "Tab", "H or F1", "Esc"}) {
        const auto at = help.find("\n  " + std::string(key) + " ", keys);
        ASSERT_NE(at, std::string::npos) << "key " << key << " missing:\n" << help.substr(keys);
        const std::string line = help.substr(at + 1, help.find('\n', at + 1) - at - 1);
        EXPECT_GT(line.find_first_not_of(' ', 2 + std::string(key).size()), 12u) << line;
        EXPECT_GT(line.size(), 30u) << "says nothing: " << line;
    }
}

TEST(App, DraggingTheBodyLiftsIt) {
    // Grab the resting sphere from above its middle and pull it up and to the left.
    const fs::path script = write_script("drag.script",
                                         "120 move 0.76 0.63\n"
                                         "121 press left\n"
                                         "122 move 0.74 0.55\n"
                                         "130 move 0.70 0.40\n"
                                         "140 move 0.66 0.30\n");
    const Result still = run_app("--size 960x600 --frames 160");
    const Result dragged = run_app("--size 960x600 --frames 160 --script " + quote(script.string()));
    ASSERT_EQ(still.exit_code, 0) << still.err;
    ASSERT_EQ(dragged.exit_code, 0) << dragged.err;
    // Left alone the sphere (radius 0.5 m) has landed and sits near the ground; held by one
    // particle and pulled up, its centre of mass rises well above that.
    EXPECT_LT(com_z(still), 0.6);
    EXPECT_GT(com_z(dragged), com_z(still) + 0.3) << "the drag did not lift the body";
}

TEST(App, AddMenuDropsBodiesThatLandOnOneAnother) {
    // A soft cube dropped beside the sphere, then a rigid ball dropped over the same spot: the
    // ball lands on the cube (soft triangles hold it), well above where the ground would.
    const fs::path script = write_script("add.script", "5 add soft_cube\n40 add rigid_ball\n");
    const Result r = run_app("--size 960x600 --frames 240 --script " + quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.summary["status"], "ok");
    ASSERT_EQ(r.summary["rigid_bodies"].size(), 1u);
    EXPECT_EQ(r.summary["rigid_bodies"][0]["name"], "ball1");
    // The ball's radius is 0.25 m: on the ground its centre would be at 0.25; on the 0.5 m cube
    // (squashed a little under it) well above that.
    EXPECT_GT(r.summary["rigid_bodies"][0]["position"][2].get<double>(), 0.55);
}

TEST(App, DraggingARigidBodyByItsEndLiftsAndTurnsIt) {
    // A plank lying on the ground; grab its right end (where it is drawn in a 960x600 window)
    // and pull up: the pull acts at the grabbed point, so the plank rises and tilts.
    const fs::path scene = scratch() / "plank.json";
    std::ofstream(scene) << "{\"rigid_bodies\": [{\"name\": \"plank\", \"shape\": \"box\", \"size\": [2.0, 0.4, 0.1],"
                            " \"mass\": 4, \"position\": [0, 0, 0.05]}]}";
    const fs::path script = write_script("plank_drag.script",
                                         "10 move 0.77 0.48\n"
                                         "11 press left\n"
                                         "12 move 0.77 0.45\n"
                                         "20 move 0.77 0.35\n"
                                         "30 move 0.77 0.25\n");
    const Result r = run_app("--scene " + quote(scene.string()) + " --size 960x600 --frames 60 --script " + quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(r.summary["rigid_bodies"].size(), 1u) << r.out;
    const auto& plank = r.summary["rigid_bodies"][0];
    EXPECT_GT(plank["position"][2].get<double>(), 0.3) << "the drag did not lift the plank";
    // How far the plank's long axis (its x) points up: R's x column, z row, 2 (x z - w y).
    const auto& q = plank["orientation"];
    const double up = 2.0 * (q[1].get<double>() * q[3].get<double>() - q[0].get<double>() * q[2].get<double>());
    EXPECT_GT(std::abs(up), 0.3) << "pulled at its end, the plank should tilt";
}

// A ctrl-click (a long press on a touch screen) anywhere on a soft ball inspects it: the ray
// meets the ball's surface and the nearest corner of the triangle it meets is taken, however far
// that particle is drawn from the pointer. A 1 m ball of 162 particles, the panel hidden: its
// particles are about 60 px apart on the screen, so a pick within 18 px of one missed at
// (0.8, 0.45), on the ball.
TEST(App, CtrlClickAnywhereOnASoftBallInspectsIt) {
    const fs::path scene = scratch() / "big_ball.json";
    std::ofstream(scene) << "{\"soft_bodies\": [{\"name\": \"ball\", \"mesh\": \"ball:2\", \"scale\": 1.0, \"up_axis\": \"z\","
                            " \"init_height\": 0.5, \"particle_mass\": 0.05, \"stiffness\": 300, \"damping\": 1.0}]}";
    for (const char* at : {"0.8 0.45", "0.71 0.5", "0.62 0.62"}) {
        const fs::path script = write_script("centre.script", std::string("1 key tab\n30 move ") + at + "\n31 press left ctrl\n32 release left\n");
        const Result r = run_app("--scene " + quote(scene.string()) + " --size 960x600 --frames 40 --script " + quote(script.string()));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(r.summary.contains("inspection")) << "ctrl-click at " << at << ": " << r.out;
    }
}

// The inspector on a particle of a cube resting on the ground: its read-out names the weight
// (Listing 8), the springs (Eq. 21), the dampers (Eq. 22), the ground and static friction
// (Eq. 24), and its terms add up to the net force the panel shows (about zero: at rest). A
// ctrl-click on empty sky stops it.
TEST(App, InspectorNamesEachForceAndTheySumToTheNet) {
    const fs::path scene = scratch() / "resting_cube.json";
    std::ofstream(scene) << "{\"mesh\": \"" << SOFTBODY_SOURCE_DIR << "/assets/meshes/cube.obj\", \"scale\": 0.3,"
                            " \"up_axis\": \"z\", \"init_height\": 0.15, \"particle_mass\": 0.1, \"stiffness\": 200,"
                            " \"damping\": 0.5}";
    const fs::path script = write_script("inspect.script", "5 inspect 0\n");
    const Result r = run_app("--scene " + quote(scene.string()) + " --size 960x600 --frames 240 --frame-time 0.02 --script " +
                             quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(r.summary.contains("inspection")) << r.out;
    const auto& in = r.summary["inspection"];
    EXPECT_TRUE(in["on_ground"].get<bool>());
    std::map<std::string, std::string> equation;
    double sum[3] = {0, 0, 0};
    for (const auto& t : in["terms"]) {
        equation[t["name"].get<std::string>()] = t["equation"].get<std::string>();
        for (int k = 0; k < 3; ++k) sum[k] += t["force"][k].get<double>();
    }
    EXPECT_EQ(equation["weight"], "Listing 8");
    EXPECT_EQ(equation["springs"], "Eq. 21");
    EXPECT_EQ(equation["dampers"], "Eq. 22");
    EXPECT_EQ(equation["friction"], "Eq. 24");
    EXPECT_EQ(equation.count("ground"), 1u);
    for (int k = 0; k < 3; ++k) {
        // The summary's floats, summed again in double: rounding only.
        EXPECT_NEAR(sum[k], in["net"][k].get<double>(), 1e-5) << "axis " << k;
        EXPECT_NEAR(in["net"][k].get<double>(), 0.0, 1e-3) << "at rest, axis " << k;  // weight 0.98 N
    }
    // ctrl-click on the sky: nothing there, and the inspector closes.
    const fs::path stop = write_script("inspect_stop.script", "5 inspect 0\n10 move 0.9 0.05\n11 press left ctrl\n12 release left\n");
    const Result stopped = run_app("--scene " + quote(scene.string()) + " --size 960x600 --frames 20 --script " +
                                   quote(stop.string()));
    ASSERT_EQ(stopped.exit_code, 0) << stopped.err;
    EXPECT_FALSE(stopped.summary.contains("inspection")) << stopped.out;
}

// Time travel: the panels hidden (a small window), the sphere is grabbed and flung (frames
// 120-160; left alone it rolls to x = 1.27 m by frame 220), then at frame 200 the
// timeline goes back 2 s (100 ticks, before the grab) and plays on. The replay carries the
// recorded drag, and the run ends bit for bit where an uninterrupted run of as many ticks does.
// Stepping back three ticks with the key (and once more with the script) and forward four
// lands on the same bits too.
TEST(App, ScrubbingBackAndPlayingOnGivesTheSameEnd) {
    const std::string drag = "0 key tab\n120 move 0.91 0.54\n121 press left\n122 move 0.88 0.50\n130 move 0.80 0.40\n"
                             "140 move 0.70 0.30\n160 release left\n";
    const fs::path plain = write_script("travel_plain.script", drag);
    const fs::path back = write_script("travel_back.script", drag + "200 rewind 2\n201 play\n");
    const fs::path steps = write_script("travel_steps.script", drag + "150 pause\n151 key comma\n152 key comma\n153 key comma\n"
                                                                      "154 step_back\n155 key period\n156 key period\n"
                                                                      "157 key period\n158 key n\n");
    const std::string common = "--size 480x300 --frame-time 0.02 ";  // small: four runs of 150-320 frames
    const Result travelled = run_app(common + "--frames 320 --script " + quote(back.string()));
    ASSERT_EQ(travelled.exit_code, 0) << travelled.err;
    const auto ticks = travelled.summary["ticks"].get<std::uint64_t>();
    EXPECT_NEAR(double(ticks), 220.0, 2.0) << "320 frames less the 100 ticks gone back";
    EXPECT_EQ(travelled.summary["history"]["newest_tick"].get<std::uint64_t>(), ticks);
    const Result straight = run_app(common + "--frames " + std::to_string(ticks) + " --script " + quote(plain.string()));
    ASSERT_EQ(straight.exit_code, 0) << straight.err;
    ASSERT_EQ(straight.summary["ticks"].get<std::uint64_t>(), ticks);
    EXPECT_EQ(travelled.summary["state_hash"], straight.summary["state_hash"]);
    EXPECT_LT(straight.summary["com"][0].get<double>(), 0.0) << "the drag should have flung the sphere back";

    const Result stepped = run_app(common + "--frames 170 --script " + quote(steps.string()));
    ASSERT_EQ(stepped.exit_code, 0) << stepped.err;
    const auto paused_at = stepped.summary["ticks"].get<std::uint64_t>();
    const Result reference = run_app(common + "--frames " + std::to_string(paused_at) + " --script " + quote(plain.string()));
    EXPECT_EQ(stepped.summary["state_hash"], reference.summary["state_hash"]);
}

// Comparing integrators: the default sphere with Verlet beside a copy stepped by explicit
// Euler (each at its own automatic substeps). Both run in lockstep; the bounce takes energy
// from both, but explicit Euler's springs pump energy in at every step, so after 3 s its total
// stands well above Verlet's (measured: 148 J against 80 J).
TEST(App, ComparedIntegratorsRunInLockstepAndExplicitEulerEndsAboveVerlet) {
    const fs::path script = write_script("compare.script", "1 compare explicit_euler\n");
    const Result r = run_app("--size 480x300 --frame-time 0.02 --frames 150 --script " + quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(r.summary.contains("compared")) << r.out;
    const auto& worlds = r.summary["compared"];
    ASSERT_EQ(worlds.size(), 2u);
    EXPECT_EQ(worlds[0]["integrator"], "verlet");
    EXPECT_EQ(worlds[1]["integrator"], "explicit_euler");
    EXPECT_EQ(worlds[0]["ticks"], worlds[1]["ticks"]);
    EXPECT_EQ(worlds[0]["ticks"], r.summary["ticks"]);
    EXPECT_EQ(worlds[1]["status"], "ok");
    const double verlet = worlds[0]["total_energy"].get<double>(), euler = worlds[1]["total_energy"].get<double>();
    EXPECT_GT(euler, 1.2 * verlet) << "explicit Euler " << euler << " J, Verlet " << verlet << " J";
}

TEST(App, PresetIsSavedAndLoadedBackAndNeverOverwritten) {
    const fs::path preset = scratch() / "presets" / "mine.json";
    fs::remove_all(preset.parent_path());
    fs::create_directories(preset.parent_path());
    const fs::path script = write_script("preset.script",
                                         "5 set stiffness 42\n"
                                         "6 save_preset " + preset.string() + "\n"
                                         "7 set stiffness 11\n"
                                         "8 load_scene " + preset.string() + "\n");
    const Result r = run_app("--frames 12 --script " + quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.summary["error"], "");
    EXPECT_FLOAT_EQ(r.summary["scene"]["soft_bodies"][0]["stiffness"].get<float>(), 42.0f);  // loaded back
    std::ifstream saved(preset);
    const auto on_disk = nlohmann::json::parse(saved);
    EXPECT_FLOAT_EQ(on_disk["soft_bodies"][0]["stiffness"].get<float>(), 42.0f);

    // Saving again to the same file without saying "overwrite" leaves it as it is.
    const fs::path again = write_script("again.script",
                                        "3 set stiffness 7\n"
                                        "4 save_preset " + preset.string() + "\n");
    const Result second = run_app("--frames 8 --script " + quote(again.string()));
    ASSERT_EQ(second.exit_code, 0) << second.err;
    EXPECT_NE(second.summary["error"].get<std::string>().find("already exists"), std::string::npos);
    std::ifstream unchanged(preset);
    EXPECT_FLOAT_EQ(nlohmann::json::parse(unchanged)["soft_bodies"][0]["stiffness"].get<float>(), 42.0f);
}

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The Graph panel's Export CSV (the script's export_csv) holds a row for the start and every
// tick the window ran: the same bytes as `softbody simulate --series` gives for the same scene
// and ticks, one record of the physics however it is run. A second export to the same file is
// refused and leaves the first as it was.
TEST(App, ExportedCsvIsTheSimulatedSeriesOfTheSameTicks) {
    const fs::path window_csv = scratch() / "window.csv", simulated_csv = scratch() / "simulated.csv";
    fs::remove(window_csv);
    fs::remove(simulated_csv);
    const std::string scene = std::string(SOFTBODY_ASSETS) + "/scenes/damper.json";
    const fs::path script = write_script("export.script", "30 export_csv " + window_csv.string() + "\n"
                                                          "34 export_csv " + window_csv.string() + "\n");
    const Result r = run_app("--scene " + quote(scene) + " --size 480x300 --frames 36 --frame-time 0.02 --script " + quote(script.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.summary["error"].get<std::string>().find("already exists"), std::string::npos) << r.out;
    const std::string window = read_bytes(window_csv);
    const auto rows = std::count(window.begin(), window.end(), '\n') - 1;  // less the header
    ASSERT_GE(rows, 25) << window;
    EXPECT_NE(window.find("time (s),kinetic (J),gravitational (J),elastic (J),dissipated (J),total (J),bob x (m)"), std::string::npos);
    const std::string command = std::string(SOFTBODY_EXE) + " simulate --scene " + quote(scene) + " --ticks " +
                                std::to_string(rows - 1) + " --series " + quote(simulated_csv.string()) + " > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    EXPECT_EQ(window, read_bytes(simulated_csv));
}

TEST(App, BadMeshPathShowsAnErrorAndKeepsRunning) {
    const fs::path shot = scratch() / "bad_mesh.png";
    const Result r = run_app("--mesh /no/such/mesh.obj --frames 20 --screenshot " + quote(shot.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.summary["error"].get<std::string>().find("/no/such/mesh.obj"), std::string::npos);
    EXPECT_EQ(r.summary["status"], "ok");
    EXPECT_GT(r.summary["ticks"].get<int>(), 0);  // the default scene runs instead

    // Loading a broken mesh later keeps the body that was there.
    const fs::path broken = scratch() / "broken.obj";
    std::ofstream(broken) << "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n";
    const fs::path script = write_script("load_bad.script", "5 load_mesh " + broken.string() + "\n");
    const Result later = run_app("--frames 20 --script " + quote(script.string()));
    ASSERT_EQ(later.exit_code, 0) << later.err;
    EXPECT_NE(later.summary["error"].get<std::string>().find("broken.obj:2"), std::string::npos);
    EXPECT_EQ(later.summary["particles"], 162);
    EXPECT_EQ(later.summary["ticks"], 16);
}

TEST(App, DivergenceIsShownNotFatal) {
    // Listing 8's constants with very light particles explode at one substep.
    const Result r = run_app("--set particle_mass=0.01 --set auto_substeps=false --frames 60");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.summary["status"], "diverged");
    EXPECT_NE(r.summary["error"].get<std::string>().find("substeps"), std::string::npos);
    for (const auto& c : r.summary["com"]) EXPECT_TRUE(std::isfinite(c.get<double>()));
}

TEST(App, MalformedScriptIsRejectedWithItsLine) {
    const fs::path script = write_script("bad.script", "1 move 0.5 0.5\n2 jump\n");
    const Result r = run_app("--frames 5 --script " + quote(script.string()));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("bad.script:2"), std::string::npos) << r.err;
}

TEST(App, SoakScriptLoopsAndEndsRunningWithFlatMemory) {
    // Two loops of the soak's script (tests/soak/soak.script: grabs, pins, divergence and
    // recovery, resets, integrator, mesh and scene switches, a missing mesh), small window.
    // The full soak is `./dev.sh soak`: 20,000 frames, 32 loops.
    const Result r = run_app("--size 480x300 --frames 1250 --script tests/soak/soak.script", SOFTBODY_SOURCE_DIR);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.summary["status"], "ok");  // a loop ends on the default scene, running
    EXPECT_EQ(r.summary["soft_bodies"][0]["mesh"], "assets/meshes/sphere.off");
    EXPECT_EQ(r.summary["error"], "");
    // Resident memory after frame 100 and at the end. Measured: 109,936 KiB and 111,400 KiB
    // (the first loop loads each mesh and scene once). 16 MiB over 1,150 frames fails a leak of
    // more than about 14 KiB a frame, such as a copy of the window's image (576 KiB); smaller
    // leaks are the renderer soak's and the sanitizers' to find.
    const auto& memory = r.summary["memory_kib"];
    ASSERT_TRUE(memory.is_object()) << r.out;
    EXPECT_GT(memory["after_warmup"].get<long>(), 0);
    EXPECT_LT(memory["end"].get<long>() - memory["after_warmup"].get<long>(), 16 * 1024);
}

// A scene's "view": opened by --lesson or by the menu, the slope lesson looks at its ramp from
// the side (yaw 0, pitch 25 degrees) and names itself in the menu; the drag lesson opens with
// the Measure panel's height scale on, and the next scene opened without one turns it off.
TEST(App, LessonsOpenWithTheirOwnViewAndMeasuringAids) {
    const Result slope = run_app("--lesson 4 --size 480x300 --frames 3");
    ASSERT_EQ(slope.exit_code, 0) << slope.err;
    EXPECT_NEAR(slope.summary["camera"]["yaw"].get<double>(), 0.0, 1e-3) << slope.out;
    EXPECT_NEAR(slope.summary["camera"]["pitch"].get<double>(), 25.0, 1e-3) << slope.out;
    EXPECT_EQ(slope.summary["lesson"]["number"], 4) << slope.out;
    EXPECT_EQ(slope.summary["tools"]["Measure"]["height_scale"], false) << slope.out;

    const Result drag = run_app("--lesson 3 --size 480x300 --frames 3");
    ASSERT_EQ(drag.exit_code, 0) << drag.err;
    EXPECT_EQ(drag.summary["tools"]["Measure"]["height_scale"], true) << drag.out;

    const fs::path script = write_script("aids.script", "1 lesson 3\n3 lesson 1\n");
    const Result then = run_app("--size 480x300 --frames 6 --script " + quote(script.string()));
    ASSERT_EQ(then.exit_code, 0) << then.err;
    EXPECT_EQ(then.summary["lesson"]["number"], 1) << then.out;
    EXPECT_EQ(then.summary["tools"]["Measure"]["height_scale"], false) << then.out;
}

// The Lessons menu, scripted ('lesson N' opens lesson N as the menu does): each lesson opens
// in order with its title, runs, and none of its closed forms disagrees with the simulation;
// the stability lesson diverges, as it predicts. Then the spring's period, measured live (every
// tick, five a frame) over 7 s, against 2 pi sqrt(m / k).
TEST(App, EachLessonOpensInOrderAndTheSpringKeepsItsPeriod) {
    for (int n = 1; n <= int(softbody::lessons().size()); ++n) {
        const fs::path script = write_script("lesson.script", "1 lesson " + std::to_string(n) + "\n");
        // 30 frames of 0.04 s: 60 ticks, 1.2 s (a small window: software GL is the slow part).
        const Result r = run_app("--size 480x300 --frames 30 --frame-time 0.04 --script " + quote(script.string()));
        ASSERT_EQ(r.exit_code, 0) << "lesson " << n << ": " << r.err;
        ASSERT_TRUE(r.summary.contains("lesson")) << "lesson " << n << ": " << r.out;
        const auto& lesson = r.summary["lesson"];
        EXPECT_EQ(lesson["number"], n);
        EXPECT_FALSE(lesson["title"].get<std::string>().empty()) << n;
        EXPECT_EQ(lesson["title"], r.summary["scene"]["title"]) << n;
        EXPECT_EQ(lesson["error"], "") << n;
        EXPECT_GT(r.summary["ticks"].get<int>(), 0) << n;
        if (n == 6) {
            EXPECT_EQ(r.summary["status"], "diverged") << "the stability lesson should explode";
        } else {
            EXPECT_EQ(r.summary["status"], "ok") << n;
            EXPECT_EQ(r.summary["error"], "") << n;
        }
        for (const auto& c : lesson["comparisons"]) {
            EXPECT_NE(c["agrees"], false) << "lesson " << n << ": " << c.dump();
        }
    }
    const fs::path script = write_script("spring.script", "1 lesson 1\n");
    const Result r = run_app("--size 480x300 --frames 70 --frame-time 0.1 --script " + quote(script.string()));  // 7 s
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto& period = r.summary["lesson"]["comparisons"][0];
    ASSERT_EQ(period["name"], "period") << r.out;
    EXPECT_NEAR(period["predicted"].get<double>(), 2.0 * 3.14159265358979 * std::sqrt(1.0 / 40.0), 1e-9);
    ASSERT_TRUE(period["measured"].is_number()) << r.out;
    EXPECT_NEAR(period["measured"].get<double>(), period["predicted"].get<double>(), 0.01 * period["predicted"].get<double>());
    EXPECT_EQ(period["agrees"], true);
    // The lesson's own controls come first: the spring constant k, in plain words with its unit,
    // where the panel draws it. Setting it changes what is predicted and what is measured.
    const Result wide = run_app("--size 1000x700 --frames 3 --script " + quote(script.string()));  // the panel open
    ASSERT_EQ(wide.exit_code, 0) << wide.err;
    const auto& controls = wide.summary["lesson"]["controls"];
    ASSERT_FALSE(controls.empty()) << r.out;
    EXPECT_EQ(controls[0]["key"], "spring.stiffness");
    EXPECT_EQ(controls[0]["label"], "spring constant k (N/m)");
    EXPECT_EQ(controls[0]["value"], "40");
    const auto& rect = controls[0]["rect"];
    EXPECT_GT(rect[2].get<double>(), 0.05) << "the slider has a width on screen";
    EXPECT_LT(rect[0].get<double>() + rect[2].get<double>(), 0.6) << "inside the panel, on the left";
    const fs::path stiffer = write_script("stiffer.script", "1 lesson 1\n2 set spring.stiffness 160\n3 reset\n");
    const Result k = run_app("--size 1000x700 --frames 70 --frame-time 0.1 --script " + quote(stiffer.string()));
    ASSERT_EQ(k.exit_code, 0) << k.err;
    EXPECT_EQ(k.summary["lesson"]["controls"][0]["value"], "160");
    const auto& shorter = k.summary["lesson"]["comparisons"][0];
    EXPECT_NEAR(shorter["predicted"].get<double>(), 2.0 * 3.14159265358979 * std::sqrt(1.0 / 160.0), 1e-9);
    ASSERT_TRUE(shorter["measured"].is_number()) << k.out;
    EXPECT_NEAR(shorter["measured"].get<double>(), shorter["predicted"].get<double>(), 0.01 * shorter["predicted"].get<double>());
    // A lesson that does not exist: an error, not an exit.
    const fs::path none = write_script("no_lesson.script", "1 lesson 99\n");
    const Result missing = run_app("--frames 5 --script " + quote(none.string()));
    ASSERT_EQ(missing.exit_code, 0) << missing.err;
    EXPECT_NE(missing.summary["error"].get<std::string>().find("no lesson 99"), std::string::npos) << missing.out;
}
