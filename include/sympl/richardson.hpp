#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/methods/richardson.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/richardson.hpp> is deprecated: include <sympl/methods/richardson.hpp>")
#endif
#include "methods/richardson.hpp"
