// Load an FCLIB problem and measure the FCLIB error of the zero reaction.
#include <fcsolve/problem/error.hpp>
#include <fcsolve/io/fclib.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: quickstart PROBLEM.hdf5\n";
    return 2;
  }
  try {
    const fcsolve::LocalProblem p = fcsolve::fclib::read_local(argv[1]);
    const fcsolve::Vector r = fcsolve::Vector::Zero(p.size());
    std::cout << "nc=" << p.num_contacts() << " error(r=0)=" << fcsolve::local_error(p, r) << "\n";
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
}
