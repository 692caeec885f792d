// The subcommands of the `softbody` executable. Each returns the process exit code.
#pragma once

namespace softbody::app {

int simulate_command(int argc, char** argv);  // softbody simulate ...: no window, no GL

}  // namespace softbody::app
