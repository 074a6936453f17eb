#pragma once
// One contact evaluated: normal law, tangential spring with Coulomb limit and
// rolling resistance. Written once for particle-particle and particle-wall
// contacts and for both dimensions; the normal law is a template parameter.
//
// Conventions: n is the unit normal from i towards j (or towards the wall),
// overlap d = r_i + r_j - |x_j - x_i| > 0, arm_i = r_i - d/2 is the distance
// from i's centre to the contact point. v_rel is the velocity of i's surface
// relative to j's at the contact point, so vn = v_rel . n > 0 when closing.
#include <cmath>
#include <limits>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct ContactHistory {
  Vec<D> tangential = Vec<D>::Zero();  ///< elastic tangential displacement, m
};

/// A moment-carrying bond's relative rotation of i against j since it was
/// made, rad: its bending part (in the contact plane; 2D the whole rotation)
/// and, in 3D, its twist about the normal.
template <int D>
struct BondRotation {
  AngVec<D> bending = AngVec<D>::Zero();
  double twist = 0.0;
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(bending, twist);
  }
};

template <int D>
struct ContactForce {
  Vec<D> force_on_i;    ///< N
  AngVec<D> torque_i;   ///< N m
  AngVec<D> torque_j;   ///< N m (about j's centre; zero for walls)
  double normal_force;  ///< N, magnitude
};

/// Removes the normal part of a history vector and keeps its length, so the
/// spring follows the rotating contact plane (as LAMMPS and YADE do). The
/// length factor 1/sqrt(1 - x), x = (h.n)^2/|h|^2, is a series for the small x
/// of one time step (first neglected term 35/128 x^4 < 3e-17).
template <int D, int K>
[[gnu::always_inline]] inline void rotate_into_plane(Eigen::Matrix<double, K, 1>& h, const Vec<D>& n) {
  if constexpr (K == D) {
    const double before = h.squaredNorm();
    // A history this small (below the smallest normal double, so also zero)
    // is left as it is: 1 / before would overflow and turn it into NaN.
    if (before < std::numeric_limits<double>::min()) return;
    const double inv_before = 1.0 / before;  // independent of n: off the critical path
    const double hn = h.dot(n);
    h -= hn * n;
    const double x = hn * hn * inv_before;
    double scale = 1.0 + x * (0.5 + x * (0.375 + x * 0.3125));
    if (x >= 1e-4) {
      const double after = h.squaredNorm();
      scale = after > 0.0 ? std::sqrt(before / after) : 1.0;
    }
    h *= scale;
  }
}

/// Evaluates one touching contact and updates its history.
///   Tangential: xi += v_t dt; F_t = -k_t xi - c_t v_t; |F_t| <= mu F_n, with
///   xi reset to the slip limit when sliding. Rolling (type C, Ai et al. 2011):
///   theta += w_roll dt; M = -k_r theta, |M| <= mu_r R* F_n, k_r = 2.25 k_n mu_r^2 R*^2.
template <int D, class Law>
[[gnu::always_inline]] inline ContactForce<D> evaluate_contact(
    const PairParameters& p, const Vec<D>& n, double overlap, double arm_i, double arm_j, const Vec<D>& v_rel,
    const AngVec<D>& omega_rel, double sqrt_m_eff, double r_eff, double dt, Vec<D>& xi, AngVec<D>* rolling) {
  const double vn = v_rel.dot(n);
  const NormalResponse nr = Law::evaluate(p, overlap, vn, sqrt_m_eff, r_eff);
  const double fn = nr.force;
  Vec<D> force = -fn * n;

  // Tangential spring-dashpot with Coulomb friction.
  const Vec<D> vt = v_rel - vn * n;
  rotate_into_plane<D, D>(xi, n);
  xi += vt * dt;
  const double kt = nr.tangential_stiffness;
  const double ct = p.tangential_damping * sqrt_m_eff * nr.sqrt_tangential_stiffness;
  Vec<D> ft = -kt * xi - ct * vt;
  const double ft_max = p.friction * fn;
  const double ft_norm2 = ft.squaredNorm();
  // Coulomb limit without branches (many contacts of a packing slide, in no
  // predictable pattern): scale is 1 when sticking; when sliding, F_t is
  // scaled onto the limit and xi set to the spring length that gives it.
  const bool sliding = ft_norm2 > ft_max * ft_max;
  const double limit = std::sqrt(ft_max * ft_max / ft_norm2);
  const double scale = sliding ? limit : 1.0;
  ft *= scale;
  const double inv_kt = nr.inv_tangential_stiffness;
  for (int k = 0; k < D; ++k) {
    const double slipped = -(ft[k] + ct * vt[k]) * inv_kt;
    xi[k] = sliding ? slipped : xi[k];
  }
  if (ft_max == 0.0) xi.setZero();
  force += ft;

  ContactForce<D> out;
  out.force_on_i = force;
  out.normal_force = fn;
  const AngVec<D> n_cross_ft = cross(n, ft);
  out.torque_i = arm_i * n_cross_ft;
  out.torque_j = arm_j * n_cross_ft;

  if (rolling != nullptr && p.rolling_friction > 0.0) {
    AngVec<D> w_roll = omega_rel;
    if constexpr (D == 3) {
      w_roll -= w_roll.dot(n) * n;  // twisting is not resisted
      rotate_into_plane<D, 3>(*rolling, n);
    }
    *rolling += w_roll * dt;
    const double kr = p.rolling_stiffness(nr.normal_stiffness, r_eff);
    AngVec<D> m = -kr * *rolling;
    const double m_max = p.rolling_friction * r_eff * fn;
    const double m_norm = m.norm();
    if (m_norm > m_max) {
      m *= (m_norm > 0.0 ? m_max / m_norm : 0.0);
      *rolling = kr > 0.0 ? AngVec<D>(-m / kr) : AngVec<D>::Zero();
    }
    out.torque_i += m;
    out.torque_j -= m;
  }
  return out;
}

/// A bond's normal force (linear spring-dashpot, in tension too: d < 0).
[[gnu::always_inline]] inline double bond_normal_force(const PairParameters& p, double overlap, double vn,
                                                       double sqrt_m_eff) {
  return p.normal_stiffness * overlap + p.normal_damping * sqrt_m_eff * p.sqrt_normal_stiffness * vn;
}

/// A bonded pair (PFC's linear contact bond; the pair's law is linear): the
/// normal spring-dashpot F_n = k_n d + c_n v_n also in tension (d < 0, the
/// grains apart), the tangential spring-dashpot without the Coulomb limit,
/// and, when the pair's bond has a moment (rotation != nullptr), a bending
/// spring M_b = -k_b theta_b on the relative rotation in the contact plane
/// and in 3D a twisting one M_tw = -k_tw theta_tw n about the normal
/// (k = ratio k_n R*^2); without, no moment (the bond turns freely, a pin).
/// The bond holds while the tension -F_n is at most the tensile strength,
/// |F_t| at most the shear strength and |M_b|, |M_tw| at most theirs, each
/// strength times this bond's factor `strength` (1 unless the strengths
/// vary, PairParameters::bond_strength_factor): then
/// the new histories are written to xi (and *rotation) and `held` is true.
/// Otherwise they are left as they were and `held` false: the caller breaks
/// the bond and evaluates the pair as an unbonded contact of this step.
template <int D>
[[gnu::always_inline]] inline ContactForce<D> evaluate_bond(const PairParameters& p, const Vec<D>& n,
                                                            double overlap, double arm_i, double arm_j,
                                                            const Vec<D>& v_rel, const AngVec<D>& omega_rel,
                                                            double sqrt_m_eff, double r_eff, double dt,
                                                            Vec<D>& xi, BondRotation<D>* rotation,
                                                            double strength, bool& held) {
  const double vn = v_rel.dot(n);
  const double fn = bond_normal_force(p, overlap, vn, sqrt_m_eff);
  const Vec<D> vt = v_rel - vn * n;
  Vec<D> h = xi;
  rotate_into_plane<D, D>(h, n);
  h += vt * dt;
  const Vec<D> ft = -p.tangential_ratio * p.normal_stiffness * h -
                    p.tangential_damping * sqrt_m_eff * p.sqrt_tangential_stiffness * vt;
  const double shear = strength * p.bond_shear;
  held = -fn <= strength * p.bond_tensile && ft.squaredNorm() <= shear * shear;
  ContactForce<D> out;
  out.force_on_i = -fn * n + ft;
  out.normal_force = fn;
  const AngVec<D> n_cross_ft = cross(n, ft);
  out.torque_i = arm_i * n_cross_ft;
  out.torque_j = arm_j * n_cross_ft;
  if (rotation != nullptr) {
    // Bending: the relative rotation in the contact plane (its history turned
    // with the plane, as the tangential one); twist: about the normal.
    BondRotation<D> r = *rotation;
    AngVec<D> w_bend = omega_rel;
    AngVec<D> moment;
    if constexpr (D == 3) {
      const double w_twist = omega_rel.dot(n);
      w_bend -= w_twist * n;
      rotate_into_plane<D, 3>(r.bending, n);
      r.twist += w_twist * dt;
      const double m_twist = -p.bond_twisting_stiffness(r_eff) * r.twist;
      held = held && std::abs(m_twist) <= strength * p.bond_twisting_strength;
      moment = m_twist * n;
    } else {
      moment.setZero();
    }
    r.bending += w_bend * dt;
    const AngVec<D> m_bend = -p.bond_bending_stiffness(r_eff) * r.bending;
    const double bending = strength * p.bond_bending_strength;
    held = held && m_bend.squaredNorm() <= bending * bending;
    moment += m_bend;
    out.torque_i += moment;
    out.torque_j -= moment;
    if (held) *rotation = r;
  }
  if (held) xi = h;
  return out;
}

}  // namespace darcydem
