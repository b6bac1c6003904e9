// Elastic blocks of linear hexahedra (hex_mesh.hpp, elastodynamics.hpp) in
// contact, small strain and small sliding:
//   node-to-plane    block 0's bottom nodes on the rigid plane z = 0;
//   node-to-surface  block 1's bottom nodes (slaves) on block 0's top face
//                    (master: bilinear quadrilaterals), linearised as in
//                    Wriggers 2006, "Computational Contact Mechanics", sec. 4.3
//                    and 9.3: the slave's projection on the master face keeps
//                    its undeformed normal e_z, its shape-function weights
//                    N_a come from the slave's current (x, y) in the master's
//                    reference grid, and
//                      gap = z_s - sum_a N_a z_a,   u = R^T (v_s - sum_a N_a v_a)
//                    with R = [e_z e_x e_y]: H's column block for a contact
//                    is +R at the slave's dofs and -N_a R at master node a's.
// Loads: gravity, and on the top face of the last block a pressure and a
// shear traction ramped up over `ramp_time`.
#pragma once

#include <fcsolve/scenes/elastodynamics.hpp>
#include <fcsolve/scenes/hex_mesh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

/// A node (slave) on the plane (masters = 0) or on a master face.
struct NodeContact {
  long node = 0;
  int masters = 0;
  std::array<long, 4> master{};
  std::array<double, 4> weight{};
  double gap = 0;
  std::uint64_t key = 0;  ///< the slave node (warm start)
};

struct ElasticLoad {
  double h = 1e-3, theta = 0.5, gravity = 9.81;
  double pressure = 5e4;   ///< Pa on the last block's top face
  double shear = 0.45;     ///< shear traction / pressure
  double shear_angle = 0;  ///< direction of the shear in the (x, y) plane
  double ramp_time = 0.05; ///< the top load reaches full strength at this time
  bool consistent_mass = false;
};

class ElasticScene {
 public:
  /// Blocks are numbered in order (first_node is set here); block 0 rests on
  /// the plane, block 1 (if any) on block 0.
  ElasticScene(std::vector<HexBlock> blocks, const ElasticLoad& load)
      : blocks_(std::move(blocks)), load_(load), dynamics_(make_dynamics()) {
    const Index n = dynamics_.dofs();
    Vector g = Vector::Zero(n);
    for (Index a = 0; a < n / 3; ++a) g[3 * a + 2] = -load.gravity;
    gravity_ = dynamics_.M() * g;  // exact for lumped and consistent mass
    top_load_ = Vector::Zero(n);
    Vector top = Vector::Zero(n);
    blocks_.back().add_top_load(1.0, top);  // unit pressure, unit shear along x
    for (Index a = 0; a < n / 3; ++a) {
      const double shear_x = top[3 * a];
      top_load_[3 * a] = load.shear * std::cos(load.shear_angle) * shear_x;
      top_load_[3 * a + 1] = load.shear * std::sin(load.shear_angle) * shear_x;
      top_load_[3 * a + 2] = top[3 * a + 2];
    }
  }

  LinearElastodynamics& dynamics() { return dynamics_; }
  const LinearElastodynamics& dynamics() const { return dynamics_; }
  const std::vector<HexBlock>& blocks() const { return blocks_; }

  /// f_ext at time t: gravity and the ramped top load.
  Vector external_force(double t) const {
    const double ramp = load_.ramp_time > 0 ? std::min(1.0, t / load_.ramp_time) : 1.0;
    return gravity_ + (ramp * load_.pressure) * top_load_;
  }

  /// Every potential contact with its current gap (the index set of
  /// contact_law.hpp picks the active ones).
  std::vector<NodeContact> candidates() const {
    std::vector<NodeContact> out;
    const Vector& x = dynamics_.displacement();
    const HexBlock& base = blocks_.front();
    for (long j = 0; j <= base.ny; ++j)
      for (long i = 0; i <= base.nx; ++i) {
        NodeContact c;
        c.node = base.node(i, j, 0);
        c.gap = base.reference(i, j, 0).z() + x[3 * c.node + 2];
        c.key = std::uint64_t(c.node);
        out.push_back(c);
      }
    if (blocks_.size() < 2) return out;
    const HexBlock& upper = blocks_[1];
    const Vec3 d = base.spacing();
    for (long j = 0; j <= upper.ny; ++j)
      for (long i = 0; i <= upper.nx; ++i) {
        NodeContact c;
        c.node = upper.node(i, j, 0);
        const Vec3 p = upper.reference(i, j, 0) + x.segment<3>(3 * c.node);
        // master element and bilinear coordinates (s, t) in [0, 1]^2
        const double gx = (p.x() - base.origin.x()) / d.x(), gy = (p.y() - base.origin.y()) / d.y();
        if (gx < 0 || gy < 0 || gx > double(base.nx) || gy > double(base.ny)) continue;  // off the face
        const long ei = std::min(long(gx), base.nx - 1), ej = std::min(long(gy), base.ny - 1);
        const double s = gx - double(ei), t = gy - double(ej);
        c.masters = 4;
        const long corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        double surface = 0;
        for (int a = 0; a < 4; ++a) {
          c.master[a] = base.node(ei + corner[a][0], ej + corner[a][1], base.nz);
          c.weight[a] = (corner[a][0] ? s : 1 - s) * (corner[a][1] ? t : 1 - t);
          surface += c.weight[a] * (base.reference(ei + corner[a][0], ej + corner[a][1], base.nz).z() +
                                    x[3 * c.master[a] + 2]);
        }
        c.gap = p.z() - surface;
        c.key = std::uint64_t(c.node);
        out.push_back(c);
      }
    return out;
  }

  /// u = R^T (v_s - sum_a N_a v_a), R = [e_z e_x e_y] (file comment).
  static Vec3 local_velocity(const NodeContact& c, const Vector& v) {
    Vec3 rel = v.segment<3>(3 * c.node);
    for (int a = 0; a < c.masters; ++a) rel -= c.weight[a] * v.segment<3>(3 * c.master[a]);
    return Vec3(rel.z(), rel.x(), rel.y());
  }

  /// Appends contact number `col`'s entries of H.
  static void add_columns(const NodeContact& c, int col, std::vector<Eigen::Triplet<double, int>>& t) {
    const auto node = [&](long nd, double sign) {
      t.emplace_back(int(3 * nd + 2), 3 * col, sign);      // normal: e_z
      t.emplace_back(int(3 * nd), 3 * col + 1, sign);      // tangent 1: e_x
      t.emplace_back(int(3 * nd + 1), 3 * col + 2, sign);  // tangent 2: e_y
    };
    node(c.node, 1.0);
    for (int a = 0; a < c.masters; ++a) node(c.master[a], -c.weight[a]);
  }

  /// The frame [e_z e_x e_y] of every contact (warm start).
  static Mat3 frame() { return (Mat3() << 0, 1, 0, 0, 0, 1, 1, 0, 0).finished(); }

 private:
  LinearElastodynamics make_dynamics() {
    long first = 0;
    for (HexBlock& b : blocks_) {
      b.first_node = first;
      first += b.nodes();
    }
    std::vector<Eigen::Triplet<double, int>> tk, tm;
    for (const HexBlock& b : blocks_) b.assemble(load_.consistent_mass, tk, tm);
    const Index n = 3 * first;
    SparseMatrix K(n, n), M(n, n);
    K.setFromTriplets(tk.begin(), tk.end());
    M.setFromTriplets(tm.begin(), tm.end());
    return LinearElastodynamics(std::move(K), std::move(M), load_.h, load_.theta);
  }

  std::vector<HexBlock> blocks_;
  ElasticLoad load_;
  LinearElastodynamics dynamics_;
  Vector gravity_, top_load_;
};

}  // namespace fcsolve::scenes
