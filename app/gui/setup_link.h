// The setup a link or a command line carries: how the world started (a lesson, a scene file, a
// mesh, the --set keys it was started with) and every key changed since, as `softbody run`
// takes them. The page turns its address's query into that command line (web/softbody-page.js),
// so the same list makes both the Share tool's link and its command line.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace softbody::app {

class Session;
struct SceneOptions;

struct Setup {
    // Option and value, in order, without the leading "--": {"lesson", "1"}, {"set", "k=160"}.
    std::vector<std::pair<std::string, std::string>> args;
    // What the setup cannot carry (a file from this device, bodies added or removed), said in a
    // sentence; empty when the setup opens to this very world.
    std::string lost;
};

// `launch` is what the app was started with (app_shell.h, launch_scene()): it names the world
// while the session still shows its first one; a world loaded later is named by its source.
Setup current_setup(const Session& session, const SceneOptions& launch);

// "lesson=1&set=spring.stiffness=160": the address's query, each value percent-encoded
// (the characters a query may hold as they are, '+' and '&' and the rest escaped).
std::string setup_query(const Setup& setup);
// "softbody run --lesson 1 --set spring.stiffness=160", each word quoted for a shell when needed.
std::string setup_command(const Setup& setup);

}  // namespace softbody::app
