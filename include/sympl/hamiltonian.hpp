#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/core/hamiltonian.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/hamiltonian.hpp> is deprecated: include <sympl/core/hamiltonian.hpp>")
#endif
#include "core/hamiltonian.hpp"
