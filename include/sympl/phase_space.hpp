#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/core/phase_space.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/phase_space.hpp> is deprecated: include <sympl/core/phase_space.hpp>")
#endif
#include "core/phase_space.hpp"
