#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/core/equations_of_motion.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/equations_of_motion.hpp> is deprecated: include <sympl/core/equations_of_motion.hpp>")
#endif
#include "core/equations_of_motion.hpp"
