// Local solver (d): semismooth Newton on the SOCCP Fischer-Burmeister
// function of one contact (formulation/fischer_burmeister.hpp: Fukushima,
// Luo & Tseng 2002), with the line search of local/semismooth_newton.hpp.
#pragma once

#include <fcsolve/formulation/fischer_burmeister.hpp>
#include <fcsolve/local/semismooth_newton.hpp>

namespace fcsolve {
namespace local {

template <class Cone>
using FischerBurmeisterNewton = SemismoothNewton<Cone, FischerBurmeisterFunction<Cone>>;

}  // namespace local
}  // namespace fcsolve
