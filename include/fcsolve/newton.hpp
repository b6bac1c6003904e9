// fcsolve's semismooth Newton family:
//   Newton<Formulation, Cone, Storage, LinearSolver>        on FC/II (W, q, mu)
//   GlobalNewton<Formulation, Cone, LinearSolver, Backend>  on FC/I (M, H, f, w, mu), W never formed
// with the one-contact formulations AlartCurnierFunction, JeanMoreauFunction,
// NaturalMapFunction and FischerBurmeisterFunction (formulation/).
//
//   fcsolve::Newton<fcsolve::AlartCurnierFunction, fcsolve::Coulomb3D> nsn;
//   nsn.settings().tol = 1e-10;
//   nsn.compute(problem);           // a LocalProblemView
//   nsn.solve(r, u);                // r: warm start in, solution out
//   if (nsn.info().converged()) ...
#pragma once

#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/formulation/fischer_burmeister.hpp>
#include <fcsolve/formulation/jean_moreau.hpp>
#include <fcsolve/formulation/natural_map.hpp>
#include <fcsolve/newton/newton_solver.hpp>
#include <fcsolve/newton/global_newton.hpp>
