#pragma once
// Walls: infinite planes, boxes and cylinders. A plane's normal points into the
// granular domain; a particle touches it when its centre is closer to the
// plane than its radius, and one behind it is pushed back out. A box wall is
// a box with its own axes (those of the grid unless the scene rotates it;
// possibly of zero thickness along one: a plate in 3D, a segment in 2D, such
// as a sheet pile, a baffle or a hopper's side); particles touch it
// from any side, on a face, an edge or a corner, along the line from the
// box's nearest point to their centre. A cylinder (3D: infinite along its
// axis; 2D: a circle, a drum) is touched from the side the scene says:
// from inside (a drum, a triaxial or permeameter cell, an oedometer ring),
// where a particle that has got outside is pushed back in, or from outside
// (a pile, a pipe in a bed). A mesh wall (3D) is a triangulated surface,
// touched from either side of each facet (walls/mesh_touches.hpp): a
// hopper, a footing, any shape an STL file gives. A wall is fixed, moves at a
// prescribed velocity, or is servo-controlled so that the load on it
// approaches a target force: a plane along its normal, a box along its
// servo_axis, a cylinder by changing its radius (a triaxial cell's
// confining wall, PFC's radial servo; without a servo its radius may change
// at a set rate). A cylinder may spin about its axis (a drum); a plane or box
// may turn about its rotation centre, which moves with it (PFC's wall spin
// about its centre of rotation, YADE's RotationEngine: a tilting table, a
// paddle, a turntable). Any wall may also oscillate about its motion (a
// shaking table). The load is what the particles put
// on it (a cylinder's: the sum of their pushes normal to it), and with
// `with_pore_water` also the pore water's thrust (a wall that displaces the
// fluid: an impermeable piston or platen).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "darcydem/core/time_series.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/walls/triangle_mesh.hpp"

namespace darcydem {

enum class WallMotion { fixed, velocity, servo };
enum class WallShape { plane, box, cylinder, mesh };

/// The harmonic part of a servo's target (stress- or force-controlled
/// cyclic loading: the cyclic triaxial, simple shear or oedometer tests of
/// PFC and YADE): amplitude sin(2 pi f s + phase), s the time since the
/// servo was set, in the target's units.
struct ServoCycle {
  double amplitude = 0.0;  ///< N, or Pa for a stress target
  double frequency = 0.0;  ///< Hz; 0: none
  double phase = 0.0;      ///< rad
  [[nodiscard]] bool active() const { return frequency > 0.0; }
  [[nodiscard]] double at(double since) const {
    return amplitude * std::sin(2.0 * std::numbers::pi * frequency * since + phase);
  }
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(amplitude, frequency, phase);
  }
};

struct ServoControl {
  double target_force = 0.0;  ///< N, compressive load wanted on the wall
  /// Pa: with `by_stress`, target_force follows target_stress times the
  /// wall's loaded area (walls/loaded_area.hpp) at every step.
  double target_stress = 0.0;
  bool by_stress = false;
  double gain = 0.0;             ///< m/(s N): wall speed per newton of load error
  double max_speed = 0.0;        ///< m/s
  bool with_pore_water = false;  ///< the load includes Wall::water_force
  /// The target in time, N (Pa with by_stress), counted from the start of
  /// the stage that set the servo (schedule.start): the schedule (a ramp or
  /// table; one point for a constant target) plus the cycle. Where it varies,
  /// Simulation::update_servo_targets sets target_force (target_stress) from
  /// it at the start of every step.
  TimeSeries schedule = TimeSeries::constant(0.0);
  ServoCycle cycle;
  [[nodiscard]] bool varies() const { return schedule.times.size() > 1 || cycle.active(); }
  [[nodiscard]] double target_at(double time) const {
    return schedule.at(time) + (cycle.active() ? cycle.at(time - schedule.start) : 0.0);
  }
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(target_force, target_stress, by_stress, gain, max_speed, with_pore_water, schedule, cycle);
  }
};

/// A harmonic translation a wall adds to its motion (YADE's
/// HarmonicMotionEngine, PFC's wall velocity set by a sine: a shaking table,
/// a vibrated bed, cyclic loading). Since `start` it has moved the wall by
/// amplitude (sin(2 pi f (t - start) + phase) - sin(phase)): phase 0 starts
/// it at its mean place moving at amplitude 2 pi f; phase -pi/2 starts it
/// at rest, at one end of its stroke.
template <int D>
struct WallOscillation {
  Vec<D> amplitude = Vec<D>::Zero();  ///< m
  double frequency = 0.0;             ///< Hz; 0: none
  double phase = 0.0;                 ///< rad
  double start = 0.0;                 ///< s, the time it began
  [[nodiscard]] bool active() const { return frequency > 0.0; }
  /// Its displacement at time t since its start, m.
  [[nodiscard]] Vec<D> displacement(double t) const {
    const double angle = 2.0 * std::numbers::pi * frequency * (t - start) + phase;
    return amplitude * (std::sin(angle) - std::sin(phase));
  }
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(amplitude, frequency, phase, start);
  }
};

/// A unit vector normal to `axis` (unit, or zero: then x's unit): the grid
/// axis least along it, made normal to it.
template <int D>
Vec<D> unit_across(const Vec<D>& axis) {
  int least = 0;
  for (int k = 1; k < D; ++k) {
    if (std::abs(axis[k]) < std::abs(axis[least])) least = k;
  }
  Vec<D> out = Vec<D>::Zero();
  out[least] = 1.0;
  out -= out.dot(axis) * axis;
  return out.normalized();
}

template <int D>
struct Wall {
  std::string name;
  Vec<D> point = Vec<D>::Zero();   ///< a point of the plane, m (a box: its centre; a cylinder: on its axis)
  Vec<D> normal = Vec<D>::Zero();  ///< unit, pointing into the domain (a box, a cylinder: unused)
  WallShape shape = WallShape::plane;
  Vec<D> half = Vec<D>::Zero();  ///< a box's half-extents, m (>= 0; from the scene)
  /// A cylinder's radius, m (> 0), its axis (3D, unit; zero in 2D, where
  /// it is a circle) and whether the particles touch it from inside.
  double radius = 0.0;
  Vec<D> axis = Vec<D>::Zero();
  bool from_inside = true;
  /// A cylinder's rate of change of radius in the last advance, m/s (its
  /// servo's, or else radius_rate), and the particles' compressive load on
  /// it, N: the sum over its contacts of the force normal to its surface,
  /// pressing it outward when touched from inside and inward from outside.
  double radial_speed = 0.0;
  double radial_load = 0.0;
  /// m/s, a cylinder's prescribed rate of change of radius when no servo
  /// sets it (the scene's radial_velocity: a cavity expansion, a
  /// strain-controlled cell).
  double radius_rate = 0.0;
  double radius_at_build = 0.0;
  /// A mesh wall's surface, in its own frame (3D; null for other walls):
  /// from the scene, shared by the copies of the wall.
  std::shared_ptr<const TriangleMesh> mesh;
  /// A box's or mesh's own axes, as the columns of a rotation (from the scene).
  Eigen::Matrix<double, D, D> axes = Eigen::Matrix<double, D, D>::Identity();
  std::uint16_t material = 0;
  WallMotion motion = WallMotion::fixed;
  Vec<D> velocity = Vec<D>::Zero();  ///< m/s (velocity mode; servo sets it)
  /// A harmonic translation on top of `velocity` (a shaking table), and
  /// its mean velocity over the step the wall last took, m/s: the
  /// oscillation's displacement over the step over its length, so that the
  /// wall is where the sine puts it, step after step.
  WallOscillation<D> oscillation;
  Vec<D> shake_velocity = Vec<D>::Zero();
  ServoControl servo;
  /// A servo-controlled box's direction of motion as its load grows short
  /// of the target (unit; a plane moves along its normal).
  Vec<D> servo_axis = Vec<D>::Zero();
  Vec<D> force = Vec<D>::Zero();  ///< N, force the particles exert on the wall
  /// N, the pore water's thrust on the wall as of the last fluid step: set
  /// on every wall that displaces the fluid by whoever steps the fluid
  /// (fluid_step, PoreFluid::wall_thrust), zero on other walls; a servo
  /// counts it with servo.with_pore_water.
  Vec<D> water_force = Vec<D>::Zero();
  Vec<D> point_at_build = Vec<D>::Zero();
  /// A cylinder's spin about its axis, rad/s (right-handed about `axis`;
  /// 2D counter-clockwise): its surface moves, its shape stays (a drum).
  /// A plane's or box's rate of turn about its rotation centre `pivot`, in
  /// 3D about `axis` (unit; zero until it is first given one; it stays when
  /// the wall stops turning): its surface moves and it turns.
  double spin = 0.0;
  /// A plane's or box's rotation centre, m: it moves with the wall's
  /// velocity (a cylinder turns about its axis through `point`).
  Vec<D> pivot = Vec<D>::Zero();
  /// N m, the moment of the particles' contacts on the wall, forces and
  /// couples, about its axis (3D; a plane's or box's: the axis of its turn
  /// through `pivot`, zero without one) or about the 2D normal through its
  /// centre of rotation: turning it takes the power -torque x spin.
  double torque = 0.0;
  /// Since the last contact list build: the angle a plane or box has
  /// turned, rad; and a plane's reach at that build, m: the farthest
  /// particle centre from its pivot plus the skin (the particles' own move
  /// rebuilds the list before that), infinite when it was not turning then.
  double turned_since_build = 0.0;
  double reach = 0.0;
  Vec<D> pivot_at_build = Vec<D>::Zero();

  /// The state a checkpoint keeps (the name comes from the scene).
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(point, normal, material, motion, velocity, servo, servo_axis, force, water_force, point_at_build, spin,
       torque, radius, radial_speed, radial_load, radius_at_build, radius_rate, axis, axes, pivot,
       turned_since_build, reach, pivot_at_build, oscillation, shake_velocity);
  }

  /// The point its turn is about: a cylinder's axis point, or a plane's or
  /// box's pivot.
  [[nodiscard]] Vec<D> centre_of_rotation() const { return shape == WallShape::cylinder ? point : pivot; }

  /// The wall's velocity at a point c of its surface: its translation, a
  /// cylinder's spin and change of radius, a plane's or box's turn.
  [[nodiscard]] Vec<D> surface_velocity(const Vec<D>& c) const {
    if (spin == 0.0 && radial_speed == 0.0) return translation_velocity();
    Vec<D> arm = c - centre_of_rotation();
    if constexpr (D == 3) arm -= arm.dot(axis) * axis;
    Vec<D> v = translation_velocity();
    if (radial_speed != 0.0) {
      const double rho = arm.norm();
      if (rho > 0.0) v += (radial_speed / rho) * arm;
    }
    if (spin == 0.0) return v;
    if constexpr (D == 2) {
      return v + spin * Vec<D>(-arm[1], arm[0]);
    } else {
      return v + spin * cross(axis, arm);
    }
  }
  /// Its translation's velocity over the last step, m/s: its motion's and
  /// its oscillation's.
  [[nodiscard]] Vec<D> translation_velocity() const { return velocity + shake_velocity; }
  /// Its angular velocity, rad/s: spin about its axis (2D: about the
  /// normal to the plane of the discs).
  [[nodiscard]] AngVec<D> angular_velocity() const {
    if constexpr (D == 2) {
      return AngVec<D>(spin);
    } else {
      return spin * axis;
    }
  }
  /// Whether it has an axis to take moments about: in 2D the normal to the
  /// plane of the discs; in 3D a cylinder's, or a plane's or box's once it
  /// was given a turn.
  [[nodiscard]] bool has_axis() const {
    if constexpr (D == 2) {
      return true;
    } else {
      return axis != Vec<D>::Zero();
    }
  }
  /// The moment about its axis through its centre of rotation of a force f
  /// at x and a couple t (3D: zero while it has no axis).
  [[nodiscard]] double moment_about_axis(const Vec<D>& x, const Vec<D>& f, const AngVec<D>& t) const {
    const Vec<D> arm = x - centre_of_rotation();
    if constexpr (D == 2) {
      return arm[0] * f[1] - arm[1] * f[0] + t[0];
    } else {
      return (cross(arm, f) + t).dot(axis);
    }
  }

  /// Where a particle centred at x stands against the wall: the gap from
  /// the wall's nearest point to x (negative when x is behind a plane or
  /// inside a box) and the unit normal from the wall towards x.
  struct Touch {
    double gap = 0.0;
    Vec<D> normal = Vec<D>::Zero();
  };
  [[nodiscard]] bool is_box() const { return shape == WallShape::box; }
  [[nodiscard]] bool is_plane() const { return shape == WallShape::plane; }
  [[nodiscard]] bool is_cylinder() const { return shape == WallShape::cylinder; }
  [[nodiscard]] bool is_mesh() const { return shape == WallShape::mesh; }
  /// Whether it moves as a rigid body along `servo_axis` under a servo and
  /// turns its own axes: a box or a mesh.
  [[nodiscard]] bool is_solid_body() const { return is_box() || is_mesh(); }

  [[nodiscard]] Touch touch(const Vec<D>& x) const {
    if (shape == WallShape::plane) return {(x - point).dot(normal), normal};
    if (shape == WallShape::cylinder) return cylinder_touch(x);
    if (shape == WallShape::mesh) return mesh_touch(x);
    // In the box's own axes.
    const Vec<D> d = axes.transpose() * (x - point);
    const Vec<D> outside = d - d.cwiseMax(-half).cwiseMin(half);
    const double g2 = outside.squaredNorm();
    if (g2 > 0.0) {
      const double g = std::sqrt(g2);
      return {g, axes * (outside / g)};
    }
    // Inside (or on) the box: out through the nearest face.
    int axis = 0;
    for (int k = 1; k < D; ++k) {
      if (half[k] - std::abs(d[k]) < half[axis] - std::abs(d[axis])) axis = k;
    }
    Touch t;
    t.gap = std::abs(d[axis]) - half[axis];
    t.normal = (d[axis] < 0.0 ? -1.0 : 1.0) * axes.col(axis);
    return t;
  }
  /// A cylinder's touch: d, x's offset from the axis across it, |d| = rho;
  /// from inside the gap is radius - rho towards -d, from outside rho -
  /// radius along d. On the axis itself (to round-off) any direction across
  /// it will do.
  [[nodiscard]] Touch cylinder_touch(const Vec<D>& x) const {
    Vec<D> d = x - point;
    if constexpr (D == 3) d -= d.dot(axis) * axis;
    const double rho = d.norm();
    Vec<D> out;
    // Within round-off of the axis d has no direction worth the name.
    if (rho > 1e-12 * radius) {
      out = d / rho;
    } else {
      out = unit_across(axis);
    }
    return from_inside ? Touch{radius - rho, -out} : Touch{rho - radius, out};
  }
  /// A mesh's touch: from its nearest facet (at most one touch per wall;
  /// the contacts take each facet's, facet_touch, and mesh_touches.hpp).
  [[nodiscard]] Touch mesh_touch(const Vec<D>& x) const {
    if constexpr (D == 3) {
      const Vec<D> local = to_local(x);
      return facet_touch_local(local, mesh->nearest(local).facet);
    } else {
      return {std::numeric_limits<double>::infinity(), Vec<D>::Zero()};
    }
  }
  /// A point in the wall's own frame (a box's or mesh's axes about its point).
  [[nodiscard]] Vec<D> to_local(const Vec<D>& x) const { return axes.transpose() * (x - point); }
  /// A mesh's touch on its facet f: from the facet's nearest point to x,
  /// towards x (on the facet itself, along its normal).
  [[nodiscard]] Touch facet_touch(const Vec<D>& x, std::uint32_t f) const {
    return facet_touch_local(to_local(x), f);
  }
  /// The same from x in the wall's own frame (to_local), for a point
  /// tried against many facets.
  [[nodiscard]] Touch facet_touch_local(const Vec<D>& local, std::uint32_t f) const {
    if constexpr (D == 3) {
      const Vec<D> out = local - mesh->closest_point(f, local);
      const double g = out.norm();
      return g > 0.0 ? Touch{g, axes * (out / g)} : Touch{0.0, axes * mesh->facet_normal[f]};
    } else {
      (void)local;
      (void)f;
      return {std::numeric_limits<double>::infinity(), Vec<D>::Zero()};
    }
  }
  /// The gap alone (touch(x).gap).
  [[nodiscard]] double gap(const Vec<D>& x) const { return touch(x).gap; }
  /// How far the wall has come towards particles since the last contact
  /// list build: along its normal for a plane, any way for a box, across
  /// its axis for a cylinder, plus the change of its radius. A plane or box
  /// that has turned: its pivot's move plus the angle times the farthest a
  /// point of it that a particle can touch stands from the pivot (a box's
  /// corner; a plane's reach, plus the pivot's move).
  [[nodiscard]] double moved_since_build() const {
    Vec<D> shift = point - point_at_build;
    if (turned_since_build > 0.0 && shape != WallShape::cylinder) {
      const double drift = (pivot - pivot_at_build).norm();
      const double arm = shape == WallShape::box    ? (point - pivot).norm() + half.norm()
                         : shape == WallShape::mesh ? (point - pivot).norm() + mesh->bounding_radius
                                                    : reach + drift;
      return drift + turned_since_build * arm;
    }
    if (shape == WallShape::plane) return std::abs(shift.dot(normal));
    if (shape == WallShape::cylinder) {
      if constexpr (D == 3) shift -= shift.dot(axis) * axis;
      return shift.norm() + std::abs(radius - radius_at_build);
    }
    return shift.norm();
  }
  /// Marks the wall's place at a contact list build.
  void mark_build() {
    point_at_build = point;
    radius_at_build = radius;
    pivot_at_build = pivot;
    turned_since_build = 0.0;
  }
  /// Turns a plane or box by `angle` (rad) about its pivot: right-handed
  /// about `axis` in 3D, counter-clockwise in 2D. Its point, normal and
  /// axes turn with it; the axes are kept orthonormal and right-handed.
  void turn(double angle) {
    Eigen::Matrix<double, D, D> r;
    if constexpr (D == 2) {
      r = Eigen::Rotation2Dd(angle).toRotationMatrix();
    } else {
      r = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    }
    point = pivot + r * (point - pivot);
    if (shape == WallShape::plane) normal = (r * normal).normalized();
    if (shape == WallShape::box || shape == WallShape::mesh) {
      axes = r * axes;
      axes.col(0).normalize();
      if constexpr (D == 2) {
        axes.col(1) = Vec<D>(-axes(1, 0), axes(0, 0));
      } else {
        axes.col(1) -= axes.col(1).dot(axes.col(0)) * axes.col(0);
        axes.col(1).normalize();
        axes.col(2) = axes.col(0).cross(axes.col(1));
      }
    }
    turned_since_build += std::abs(angle);
  }
  /// The direction the wall moves in to load the particles more: a
  /// plane's normal, a box's servo_axis (a cylinder's servo changes its
  /// radius instead).
  [[nodiscard]] Vec<D> push_direction() const { return shape == WallShape::plane ? normal : servo_axis; }
  /// Compressive load on the wall (N): a cylinder's radial_load; otherwise
  /// the force's component against push_direction(), the particles' and,
  /// with servo.with_pore_water, the pore water's.
  [[nodiscard]] double load() const {
    if (shape == WallShape::cylinder) return radial_load;
    const Vec<D> f = servo.with_pore_water ? Vec<D>(force + water_force) : force;
    return -f.dot(push_direction());
  }

  /// Updates the servo velocity from the last load and moves the wall over
  /// the step from `time` to time + dt. A cylinder's servo shrinks it
  /// (touched from inside) or grows it (from outside) while the load is
  /// short of the target.
  void advance(double dt, double time) {
    shake_velocity = oscillation.active()
                         ? Vec<D>((oscillation.displacement(time + dt) - oscillation.displacement(time)) / dt)
                         : Vec<D>::Zero();
    if (motion == WallMotion::servo) {
      double speed = servo.gain * (servo.target_force - load());
      if (speed > servo.max_speed) speed = servo.max_speed;
      if (speed < -servo.max_speed) speed = -servo.max_speed;
      if (shape == WallShape::cylinder) {
        velocity.setZero();
        radial_speed = from_inside ? -speed : speed;
      } else {
        velocity = speed * push_direction();
      }
    } else {
      radial_speed = shape == WallShape::cylinder ? radius_rate : 0.0;
      if (motion == WallMotion::fixed) velocity.setZero();
    }
    point += translation_velocity() * dt;
    pivot += translation_velocity() * dt;
    radius += radial_speed * dt;
    if (spin != 0.0 && shape != WallShape::cylinder) turn(spin * dt);
  }
};

/// Particle-wall candidates: for each particle, the walls within its radius
/// plus the skin, with their contact history (CSR by particle).
template <int D>
struct WallContactList {
  std::vector<std::uint32_t> offset;          ///< N+1
  std::vector<std::uint16_t> wall;            ///< wall index of each candidate
  std::vector<std::uint32_t> facet;           ///< a mesh wall's facet (0 for other walls)
  std::vector<Vec<D>> tangential;             ///< tangential history
  std::vector<AngVec<D>> rolling;             ///< rolling history (empty when unused)
  std::vector<Vec<D>> force_on_particle;      ///< this step's force, N
  std::vector<AngVec<D>> torque_on_particle;  ///< this step's torque about the particle's centre, N m

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(offset, wall, facet, tangential, rolling, force_on_particle, torque_on_particle);
  }

  /// old_index[i] (if given) is the index particle i had at the last build.
  void build(const std::vector<Vec<D>>& position, const std::vector<double>& radius,
             std::vector<Wall<D>>& walls, double skin, bool keep_rolling,
             const std::vector<std::uint32_t>* old_index = nullptr);
  [[nodiscard]] std::size_t memory_bytes() const {
    return offset.capacity() * sizeof(std::uint32_t) + wall.capacity() * sizeof(std::uint16_t) +
           facet.capacity() * sizeof(std::uint32_t) + tangential.capacity() * sizeof(Vec<D>) +
           rolling.capacity() * sizeof(AngVec<D>) + force_on_particle.capacity() * sizeof(Vec<D>) +
           torque_on_particle.capacity() * sizeof(AngVec<D>);
  }
};

}  // namespace darcydem
