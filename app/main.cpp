// softbody: a soft-body physics demo after Listing 8 of the real-time game physics addendum.
//
//   softbody                       the interactive demo with the default scene
//   softbody run [options]         the interactive demo with a chosen scene
//   softbody simulate [options]    physics only, prints a JSON summary
//   softbody render [options]      images and videos, headless
//   softbody bench [options]       timings of the physics
//   softbody lessons [--json]      the lessons, in the addendum's order
//   softbody keys [--markdown]     every key: type, unit, range, default, equation, meaning
//
// Each subcommand lives in its own cmd_*.cpp; this file only dispatches and turns errors into
// one line on stderr and an exit code.
#include <exception>
#include <iostream>
#include <string>
#include <string_view>

#include "cli.h"
#include "commands.h"
#include "crash_report.h"
#include "physics/error.h"

namespace {

constexpr const char* kUsage =
    "usage: softbody [COMMAND] [OPTIONS]\n"
    "Commands ('softbody COMMAND --help' lists its options, a line each with its default):\n"
    "  run        the interactive demo, in a window (the command when none is given)\n"
    "  simulate   the physics alone, no window or GL: prints one JSON object\n"
    "  render     PNG images, an animation's frames or an MP4 video, drawn headless\n"
    "  bench      timings of the physics on the scenes the app opens\n"
    "  lessons    the lessons, in the addendum's order\n"
    "  keys       every key of the world, soft bodies, rigid bodies and springs\n"
    "Every command takes --scene FILE, --mesh FILE and --set KEY=VALUE (lessons, keys and bench excepted).";

int dispatch(int argc, char** argv) {
    using namespace softbody::app;
    const std::string_view command = argc > 1 ? argv[1] : "";
    if (command.empty() || (command.starts_with("--") && command != "--help")) return run_command(argc, argv, 1);
    if (command == "run") return run_command(argc, argv, 2);
    if (command == "simulate") return simulate_command(argc, argv);
    if (command == "render") return render_command(argc, argv);
    if (command == "bench") return bench_command(argc, argv);
    if (command == "lessons") return lessons_command(argc, argv);
    if (command == "keys") return keys_command(argc, argv);
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << kUsage << "\n";
        return kOk;
    }
    throw UsageError("unknown command '" + std::string(command) + "'\n" + kUsage);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace softbody::app;
    install_crash_report();
    try {
        return dispatch(argc, argv);
    } catch (const UsageError& e) {
        // One line: the problem, and where the full usage is.
        std::string message = e.what();
        message = message.substr(0, message.find('\n'));
        const std::string_view first = argc > 1 ? argv[1] : "";
        const bool known = first == "simulate" || first == "render" || first == "bench" || first == "run" || first == "lessons" || first == "keys";
        const std::string command = known ? " " + std::string(first) : "";
        std::cerr << "softbody: " << message << " (see 'softbody" << command << " --help')\n";
        return kBadInput;
    } catch (const softbody::InputError& e) {
        std::cerr << "softbody: " << e.what() << "\n";
        return kBadInput;
    } catch (const std::bad_alloc&) {
        std::cerr << "softbody: out of memory\n";
        return kRuntimeFailure;
    } catch (const std::exception& e) {
        std::cerr << "softbody: " << e.what() << "\n";
        return kRuntimeFailure;
    }
}
