// softbody render in a build without the renderer (SOFTBODY_BUILD_GUI=OFF).
#include "cli.h"
#include "commands.h"

namespace softbody::app {

int render_command(int, char**) {
    throw UsageError("render: this softbody was built without the renderer (SOFTBODY_BUILD_GUI=OFF)");
}

}  // namespace softbody::app
