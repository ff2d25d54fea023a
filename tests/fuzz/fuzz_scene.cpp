// libFuzzer target: any bytes as a scene file. Everything the program does
// with a scene before it runs anything (parse, build the system, check every
// method against the system, check the run size) either succeeds or throws
// sympl::error; any other exception, crash or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include <sympl/core/error.hpp>

#include "methods/run_plan.hpp"
#include "reading/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > sympl::app::max_scene_bytes) return 0;  // load_scene refuses these before parsing
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const sympl::app::scene s = sympl::app::parse_scene(text, "fuzz.toml");
        const sympl::app::runnable_system p = sympl::app::system_of(s);
        sympl::app::check_run_size(sympl::app::plan_runs(s, p, sympl::app::sweep_use::whole), sympl::app::default_max_steps);
    } catch (const sympl::error&) {
    }
    return 0;
}
