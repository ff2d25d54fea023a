#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/core/error.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/error.hpp> is deprecated: include <sympl/core/error.hpp>")
#endif
#include "core/error.hpp"
