// The subcommands of the `softbody` executable. Each returns the process exit code.
#pragma once

namespace softbody::app {

int run_command(int argc, char** argv, int first);  // softbody [run] ...: the desktop demo
int simulate_command(int argc, char** argv);  // softbody simulate ...: no window, no GL
int render_command(int argc, char** argv);    // softbody render ...: PNGs, headless (OSMesa)
int bench_command(int argc, char** argv);     // softbody bench ...: physics timings, no GL
int lessons_command(int argc, char** argv);   // softbody lessons [--json]: the lessons in order
int keys_command(int argc, char** argv);      // softbody keys [--markdown|--json]: every key

}  // namespace softbody::app
