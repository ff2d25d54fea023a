#pragma once
// Machine code for a scene's formulas: the C source that formula_code.hpp
// writes from the parsed trees, compiled once per run by the compiler sympl
// itself was built with, into a private temporary folder, and loaded. The
// compiler is started directly (posix_spawn, an argument list: no shell) on
// files this process created new in a folder only it can write, which are
// removed as soon as the library is loaded. Where no compiler is found, the
// formulas run on the interpreter (formula_eval.hpp), about 50 times slower,
// and the run says so (docs/formulas.md).
#include <memory>
#include <stdexcept>
#include <string>

namespace sympl::app::formulas {

// A loaded library of compiled formulas; closed when its last owner goes.
class machine_code {
public:
    // The address of one of its functions; a missing one is an error.
    void* function(const std::string& name) const;

    std::shared_ptr<void> library;
    double seconds = 0;  // what compiling and loading took
};

// Compiled source, or the reason none could be made (no compiler where
// sympl was built, the compiler failed: its first lines of output).
struct compiled_or_reason {
    std::shared_ptr<const machine_code> code;
    std::string reason;
};

compiled_or_reason compile_c(const std::string& source);

// The compiler formulas are compiled with (sympl's own, set when it was built).
const char* formula_compiler();

}  // namespace sympl::app::formulas
