// Deprecated location: the error measure lives beside the problems it
// measures, in <fcsolve/problem/error.hpp> (core/ includes nothing above it:
// docs/architecture.md, "Layers"). This header only forwards, so that
// existing `#include <fcsolve/core/error.hpp>` lines keep compiling; include
// problem/error.hpp in new code.
#pragma once

#include <fcsolve/problem/error.hpp>
