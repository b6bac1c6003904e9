// fcsolve: ADMM on FC/II with De Saxce's shift (Acary, Bremond & Huber 2018).
#pragma once

#include <fcsolve/admm/admm_solver.hpp>
#include <fcsolve/cone/cones.hpp>
#include <fcsolve/storage/storage.hpp>
