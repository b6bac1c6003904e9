// Warm start of a contact solver from the previous step's reactions, matched
// by a contact's identity (a body pair, a node) rather than its position in
// the list: contacts appear, vanish and are renumbered from step to step.
//
// Impulses are kept in world coordinates, so that a contact whose frame
// turned between two steps starts from the projection of the same impulse
// on its new frame (frames are not continuous in general).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>

namespace fcsolve::scenes {

class WarmStart {
 public:
  using Key = std::uint64_t;
  using Vec3 = Eigen::Vector3d;
  using Frame = Eigen::Matrix3d;  ///< columns: normal, tangent 1, tangent 2

  void clear() { previous_.clear(); }

  /// The previous impulse of contact `key` in `frame`'s coordinates (zero for
  /// a new contact).
  Vec3 initial(Key key, const Frame& frame) const {
    const auto it = previous_.find(key);
    return it == previous_.end() ? Vec3::Zero() : Vec3(frame.transpose() * it->second);
  }
  bool known(Key key) const { return previous_.count(key) > 0; }

  /// Starts a new step's record (call record() for every contact after the solve).
  void begin_record() { next_.clear(); }
  void record(Key key, const Frame& frame, const Vec3& r_local) { next_[key] = frame * r_local; }
  void end_record() { previous_.swap(next_); }

 private:
  std::unordered_map<Key, Vec3> previous_, next_;
};

}  // namespace fcsolve::scenes
