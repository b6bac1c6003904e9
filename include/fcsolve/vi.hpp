// fcsolve: projection methods on the VI form of FC/II (fixed point,
// extragradient, self-adaptive step).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/storage/storage.hpp>
#include <fcsolve/vi/projected_fixed_point.hpp>
