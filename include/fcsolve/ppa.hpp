// fcsolve's proximal point method on FC/II: what users include.
//
//   #include <fcsolve/ppa.hpp>
//   fcsolve::ProximalPoint<fcsolve::Coulomb3D> ppa;   // inner: semismooth Newton (Alart-Curnier)
//   ppa.settings().tol = 1e-10;
//   ppa.compute(problem);          // a LocalProblem or LocalProblemView
//   ppa.solve(r, u);               // r: warm start in, solution out
//   if (ppa.info().converged()) ...
//
// The second template argument is the inner solver of the subproblems
// FC/II(W + alpha I, q - alpha r_k): any FC/II solver of the contract, e.g.
// fcsolve::Nsgs<Cone, BlockSparseStorage<d>> or a Newton with another
// storage (DenseStorage for a few contacts).
//
// fcsolve::ProximalPointGlobal<Cone> is the same method on FC/I in (v, r),
// W never formed: compute(GlobalProblemView), solve(r, v); its subproblems
// are FC/I with a contact compliance alpha, solved by GlobalNewton.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/nsgs.hpp>
#include <fcsolve/ppa/proximal_point.hpp>
#include <fcsolve/ppa/proximal_point_global.hpp>
