// softbody keys: the table of keys (physics/keys.h), every key of the world, of a soft body, of
// a rigid body and of a spring with its type, unit, valid range, default, equation, meaning
// and when it applies. As text, as the Markdown tables the documents hold (a test compares
// them), or as JSON.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cli.h"
#include "commands.h"
#include "physics/keys.h"

namespace softbody::app {

int keys_command(int argc, char** argv) {
    CLI::App app("Lists every key: the world's (--set KEY=VALUE), and each soft body's, rigid body's and spring's\n"
                 "(--set NAME.KEY=VALUE; a soft body's key without a name sets it on every soft body).",
                 "softbody keys");
    configure(app);
    bool markdown = false, as_json = false;
    app.add_flag("--markdown", markdown, "Markdown tables, one per kind of thing (what the documents hold)");
    app.add_flag("--json", as_json, "one JSON array of every key with its range, default and slider");
    app.footer(exit_codes_help(false));
    if (!parse(app, argc, argv, 2)) return kOk;
    if (markdown && as_json) throw UsageError("give --markdown or --json, not both");
    std::cout << (markdown ? keys_markdown() : as_json ? keys_json() : keys_text());
    return kOk;
}

}  // namespace softbody::app
