// fcsolve: the fixed points on the friction threshold: Tresca's
// (TrescaFixedPoint) and Panagiotopoulos' (Panagiotopoulos). De Saxce's
// fixed point is ProjectedFixedPoint with StepRule::Fixed (vi.hpp).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/fixed_point/panagiotopoulos.hpp>
#include <fcsolve/fixed_point/tresca_fixed_point.hpp>
#include <fcsolve/storage/storage.hpp>
#include <fcsolve/vi.hpp>
