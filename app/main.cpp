// softbody: a soft-body physics demo after Listing 8 of the real-time game physics addendum.
//
//   softbody                       the interactive demo with the default scene
//   softbody run [options]         the interactive demo with a chosen scene
//   softbody simulate [options]    physics only, prints a JSON summary
//   softbody lessons [--json]      the lessons, in the addendum's order
//
// Each subcommand lives in its own cmd_*.cpp; this file only dispatches and turns errors into
// one line on stderr and an exit code.
#include <exception>
#include <iostream>
#include <string>
#include <string_view>

#include "cli.h"
#include "commands.h"
#include "physics/error.h"

namespace {

constexpr const char* kUsage =
    "usage: softbody [run] [--scene FILE] [--mesh FILE] [--set KEY=VALUE]...\n"
    "       softbody simulate [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... (--seconds T | --ticks N)\n"
    "                         [--dump FILE.csv] [--dump-every K] [--threads N]\n"
    "       softbody render [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... --at T1,T2,... --out DIR [options]\n"
    "       softbody render [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... --seconds T --video FILE.mp4 [options]\n"
    "       softbody bench [--quick] [--json] [--sizes N,N,...] [options]\n"
    "       softbody lessons [--json]\n"
    "Run 'softbody <command> --help' for a command's options.";

int dispatch(int argc, char** argv) {
    using namespace softbody::app;
    const std::string_view command = argc > 1 ? argv[1] : "";
    if (command.empty() || (command.starts_with("--") && command != "--help")) return run_command(argc, argv, 1);
    if (command == "run") return run_command(argc, argv, 2);
    if (command == "simulate") return simulate_command(argc, argv);
    if (command == "render") return render_command(argc, argv);
    if (command == "bench") return bench_command(argc, argv);
    if (command == "lessons") return lessons_command(argc, argv);
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << kUsage << "\n";
        return kOk;
    }
    throw UsageError("unknown command '" + std::string(command) + "'\n" + kUsage);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace softbody::app;
    try {
        return dispatch(argc, argv);
    } catch (const UsageError& e) {
        // One line: the problem, and where the full usage is.
        std::string message = e.what();
        message = message.substr(0, message.find('\n'));
        const std::string_view first = argc > 1 ? argv[1] : "";
        const bool known = first == "simulate" || first == "render" || first == "bench" || first == "run" || first == "lessons";
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
