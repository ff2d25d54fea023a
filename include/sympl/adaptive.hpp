#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/methods/adaptive.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/adaptive.hpp> is deprecated: include <sympl/methods/adaptive.hpp>")
#endif
#include "methods/adaptive.hpp"
