// fcsolve's nonsmooth Gauss-Seidel family: what users include.
//
//   #include <fcsolve/nsgs.hpp>
//   fcsolve::Nsgs<fcsolve::Coulomb3D, fcsolve::BlockSparseStorage<3>> nsgs;
//   nsgs.settings().tol = 1e-8;
//   nsgs.compute(problem);          // a LocalProblem or LocalProblemView
//   nsgs.solve(r, u);               // r: warm start in, solution out
//   if (nsgs.info().converged()) ...
//
// The third template argument picks the local (one-contact) solver:
// local::Projection, local::ProjectionIterative, local::Enumerative,
// local::AlartCurnierNewton, local::FischerBurmeisterNewton, local::Hybrid,
// local::AlartCurnierBacktracking (the hybrid Newton's fallback).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/local/alart_curnier_backtracking.hpp>
#include <fcsolve/local/alart_curnier_newton.hpp>
#include <fcsolve/local/enumerative.hpp>
#include <fcsolve/local/fischer_burmeister_newton.hpp>
#include <fcsolve/local/hybrid.hpp>
#include <fcsolve/local/projection.hpp>
#include <fcsolve/local/projection_iterative.hpp>
#include <fcsolve/nsgs/nsgs_solver.hpp>
#include <fcsolve/storage/storage.hpp>
