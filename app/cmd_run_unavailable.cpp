// softbody run, in a build without the renderer and window (SOFTBODY_BUILD_GUI=OFF).
#include "cli.h"
#include "commands.h"

namespace softbody::app {

int run_command(int, char**, int) {
    throw UsageError("this build has no window (configured with SOFTBODY_BUILD_GUI=OFF); use 'softbody simulate'");
}

}  // namespace softbody::app
