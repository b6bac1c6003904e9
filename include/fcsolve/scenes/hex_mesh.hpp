// Linear elasticity on a regular mesh of trilinear hexahedra (small strain):
// the element stiffness and mass (Hughes 2000, "The Finite Element Method",
// sec. 3.5, 2 x 2 x 2 Gauss points) and their assembly for a box-shaped
// block [origin, origin + size] of nx x ny x nz elements. Unknowns: 3 per
// node, (node, component) -> 3 node + component; a block's nodes are
// numbered from `first_node` so that several blocks share one system.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/scenes/geometry.hpp>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <array>
#include <cmath>
#include <vector>

namespace fcsolve::scenes {

using Element24 = Eigen::Matrix<double, 24, 24>;

struct Material {
  double young = 1e6;    ///< Pa
  double poisson = 0.3;
  double density = 1000; ///< kg/m^3
};

/// The (xi, eta, zeta) signs of the 8 nodes of the reference hexahedron.
constexpr std::array<std::array<int, 3>, 8> kHexCorner = {{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
    {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};

/// Stiffness Ke and consistent mass Me of one dx x dy x dz hexahedron.
inline void hex_element_matrices(const Material& mat, double dx, double dy, double dz, Element24& Ke,
                                 Element24& Me) {
  const double E = mat.young, nu = mat.poisson;
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();  // isotropic, Voigt
  const double c = E / ((1 + nu) * (1 - 2 * nu));
  D.topLeftCorner<3, 3>().setConstant(c * nu);
  for (int i = 0; i < 3; ++i) D(i, i) = c * (1 - nu);
  for (int i = 3; i < 6; ++i) D(i, i) = c * (1 - 2 * nu) / 2;  // engineering shear strains
  const double g = 1.0 / std::sqrt(3.0);
  const double detJ = dx * dy * dz / 8.0;  // the map is diagonal: J = diag(dx, dy, dz) / 2
  Ke.setZero();
  Me.setZero();
  for (int gp = 0; gp < 8; ++gp) {
    const double xi = g * kHexCorner[gp][0], eta = g * kHexCorner[gp][1], zeta = g * kHexCorner[gp][2];
    Eigen::Matrix<double, 6, 24> B = Eigen::Matrix<double, 6, 24>::Zero();
    Eigen::Matrix<double, 8, 1> N;
    for (int a = 0; a < 8; ++a) {
      const double sa = kHexCorner[a][0], ta = kHexCorner[a][1], ua = kHexCorner[a][2];
      N[a] = (1 + sa * xi) * (1 + ta * eta) * (1 + ua * zeta) / 8;
      const double Nx = sa * (1 + ta * eta) * (1 + ua * zeta) / 8 * 2 / dx;
      const double Ny = ta * (1 + sa * xi) * (1 + ua * zeta) / 8 * 2 / dy;
      const double Nz = ua * (1 + sa * xi) * (1 + ta * eta) / 8 * 2 / dz;
      // rows: e_xx, e_yy, e_zz, g_yz, g_xz, g_xy
      B(0, 3 * a) = Nx;
      B(1, 3 * a + 1) = Ny;
      B(2, 3 * a + 2) = Nz;
      B(3, 3 * a + 1) = Nz;
      B(3, 3 * a + 2) = Ny;
      B(4, 3 * a) = Nz;
      B(4, 3 * a + 2) = Nx;
      B(5, 3 * a) = Ny;
      B(5, 3 * a + 1) = Nx;
    }
    Ke += B.transpose() * D * B * detJ;
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < 3; ++i) Me(3 * a + i, 3 * b + i) += mat.density * N[a] * N[b] * detJ;
  }
}

/// A box-shaped block of nx x ny x nz hexahedra.
struct HexBlock {
  Vec3 origin = Vec3::Zero();
  Vec3 size = Vec3(0.4, 0.4, 0.2);
  long nx = 8, ny = 8, nz = 4;
  Material material;
  long first_node = 0;

  long nodes() const { return (nx + 1) * (ny + 1) * (nz + 1); }
  long node(long i, long j, long k) const { return first_node + i + (nx + 1) * (j + (ny + 1) * k); }
  Vec3 spacing() const { return Vec3(size.x() / double(nx), size.y() / double(ny), size.z() / double(nz)); }
  Vec3 reference(long i, long j, long k) const {
    return origin + spacing().cwiseProduct(Vec3(double(i), double(j), double(k)));
  }

  /// Appends K's and M's triplets (M lumped by row sums unless `consistent`:
  /// m / 8 per node of a hexahedron). All elements are translates of each
  /// other: their matrices are computed once.
  void assemble(bool consistent, std::vector<Eigen::Triplet<double, int>>& tk,
                std::vector<Eigen::Triplet<double, int>>& tm) const {
    const Vec3 d = spacing();
    Element24 Ke, Me;
    hex_element_matrices(material, d.x(), d.y(), d.z(), Ke, Me);
    if (!consistent) {
      const Eigen::Matrix<double, 24, 1> lumped = Me.rowwise().sum();
      Me = lumped.asDiagonal();
    }
    for (long k = 0; k < nz; ++k)
      for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) {
          std::array<int, 24> dof;
          for (int a = 0; a < 8; ++a) {
            const long nd = node(i + (kHexCorner[a][0] > 0), j + (kHexCorner[a][1] > 0), k + (kHexCorner[a][2] > 0));
            for (int c = 0; c < 3; ++c) dof[3 * a + c] = int(3 * nd + c);
          }
          for (int r = 0; r < 24; ++r)
            for (int c = 0; c < 24; ++c) {
              tk.emplace_back(dof[r], dof[c], Ke(r, c));
              if (Me(r, c) != 0.0) tm.emplace_back(dof[r], dof[c], Me(r, c));
            }
        }
  }

  /// Adds the top face's nodal forces for a unit pressure (down) and a
  /// shear traction `shear` along x: area / 4 per node and quadrilateral.
  void add_top_load(double shear, Vector& load) const {
    const Vec3 d = spacing();
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i)
        for (int a = 0; a < 4; ++a) {
          const long nd = node(i + (a == 1 || a == 2), j + (a >= 2), nz);
          load[3 * nd] += shear * d.x() * d.y() / 4;
          load[3 * nd + 2] -= d.x() * d.y() / 4;
        }
  }
};

}  // namespace fcsolve::scenes
