// Downstream use of an installed fcsolve: read an FCLIB file, solve it with
// the extragradient VI solver, print the FCLIB error.
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/vi.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const fcsolve::LocalProblem p = fcsolve::fclib::read_local(argv[1]);
  fcsolve::ProjectedFixedPoint<fcsolve::Coulomb3D, fcsolve::SparseStorage<3>> solver;
  solver.settings().max_iter = 100000;
  solver.compute(p);
  fcsolve::Vector r = fcsolve::Vector::Zero(p.size()), u(p.size());
  const auto& info = solver.solve(r, u);
  std::cout << "status=" << fcsolve::to_string(info.status)
            << " error=" << fcsolve::local_error(p, r) << "\n";
  return info.converged() ? 0 : 1;
}
