// fcsolve: ADMM with De Saxce's shift (Acary, Bremond & Huber 2018), on FC/II
// (Admm) and on FC/I in (v, r) (AdmmGlobal).
#pragma once

#include <fcsolve/admm/admm_global.hpp>
#include <fcsolve/admm/admm_solver.hpp>
#include <fcsolve/cone/cones.hpp>
#include <fcsolve/storage/storage.hpp>
