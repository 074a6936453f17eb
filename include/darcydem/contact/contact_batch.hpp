#pragma once
// Linear spring-dashpot contacts evaluated a batch at a time, for the
// compiler to vectorise: the inputs of up to `capacity` pairs are copied into
// arrays (structure of arrays), one loop without branches computes every
// pair's force, torques and new history, and the caller adds the results in
// pair order. It computes what evaluate_contact<D, LinearSpringDashpot>
// (contact_kernel.hpp) computes, without rolling resistance, for touching and
// non-touching pairs alike (a non-touching pair gets zero force and history).
// Same operations for every pair, whatever the thread count or batch
// boundaries, so results stay deterministic.
#include <cmath>
#include <cstdint>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct LinearContactBatch {
  static constexpr int capacity = 64;
  static constexpr int R = rotation_dim<D>;
  int size = 0;
  // Inputs.
  alignas(64) double d[D][capacity];   ///< x_j - x_i, m
  alignas(64) double v[D][capacity];   ///< v_i - v_j, m/s
  alignas(64) double wi[R][capacity];  ///< rad/s
  alignas(64) double wj[R][capacity];
  alignas(64) double ri[capacity];
  alignas(64) double rj[capacity];
  alignas(64) double inv_m[capacity];  ///< 1/m_i + 1/m_j (0: both fixed, no contact)
  alignas(64) double h[D][capacity];   ///< tangential history at the last step
  alignas(64) double kn[capacity];     ///< N/m
  alignas(64) double cn[capacity];     ///< gamma_n sqrt(k_n)
  alignas(64) double kt[capacity];     ///< N/m
  alignas(64) double ct[capacity];     ///< gamma_t sqrt(k_t)
  alignas(64) double inv_kt[capacity];
  alignas(64) double mu[capacity];
  // Outputs.
  alignas(64) double h_new[D][capacity];  ///< tangential history after this step
  alignas(64) double f[D][capacity];      ///< force on i, N
  alignas(64) double ti[R][capacity];     ///< torque on i, N m
  alignas(64) double tj[R][capacity];     ///< torque on j, N m

 private:
  // Between the two stages of evaluate_with.
  alignas(64) double s_n[D][capacity];
  alignas(64) double s_vt[D][capacity];
  alignas(64) double s_h[D][capacity];
  alignas(64) double s_fn[capacity];
  alignas(64) double s_sqrt_m[capacity];
  alignas(64) double s_arm_i[capacity];
  alignas(64) double s_arm_j[capacity];
  alignas(64) double s_on[capacity];

 public:
  void set_parameters(int p, const PairParameters& pp) {
    kn[p] = pp.normal_stiffness;
    cn[p] = pp.normal_damping * pp.sqrt_normal_stiffness;
    kt[p] = pp.tangential_ratio * pp.normal_stiffness;
    ct[p] = pp.tangential_damping * pp.sqrt_tangential_stiffness;
    inv_kt[p] = pp.inv_tangential_stiffness;
    mu[p] = pp.friction;
  }

  /// Evaluates the batch. With `uniform` given, every pair has its
  /// parameters (one material pair in the scene) and set_parameters is not
  /// needed.
  void evaluate(double dt, const PairParameters* uniform);

 private:
  template <bool Uniform>
  void evaluate_with(double dt, const PairParameters& u);
};

template <int D>
void LinearContactBatch<D>::evaluate(double dt, const PairParameters* uniform) {
  if (uniform != nullptr) {
    evaluate_with<true>(dt, *uniform);
  } else {
    evaluate_with<false>(dt, PairParameters{});
  }
}

template <int D>
template <bool Uniform>
void LinearContactBatch<D>::evaluate_with(double dt, const PairParameters& u) {
  const int count = size;
  const double u_kn = u.normal_stiffness;
  const double u_cn = u.normal_damping * u.sqrt_normal_stiffness;
  const double u_kt = u.tangential_ratio * u.normal_stiffness;
  const double u_ct = u.tangential_damping * u.sqrt_tangential_stiffness;
  const double u_inv_kt = u.inv_tangential_stiffness;
  const double u_mu = u.friction;
#pragma GCC ivdep
  for (int p = 0; p < count; ++p) {
    const double p_kn = Uniform ? u_kn : kn[p];
    const double p_cn = Uniform ? u_cn : cn[p];
    double dist2 = 0.0;
    for (int k = 0; k < D; ++k) dist2 += d[k][p] * d[k][p];
    const double reach = ri[p] + rj[p];
    const bool touch = (dist2 < reach * reach) & (inv_m[p] > 0.0);
    // Safe values for pairs that do not touch (their results are discarded).
    const double safe_dist2 = touch ? dist2 : 1.0;
    const double safe_inv_m = touch ? inv_m[p] : 1.0;
    // One division for 1/|d| and sqrt(m_eff) = 1/sqrt(1/m_i + 1/m_j).
    const double root_dist = std::sqrt(safe_dist2);
    const double root_inv_m = std::sqrt(safe_inv_m);
    const double both = 1.0 / (root_dist * root_inv_m);
    const double inv_dist = both * root_inv_m;
    const double sqrt_m = both * root_dist;
    double n[D];
    for (int k = 0; k < D; ++k) n[k] = d[k][p] * inv_dist;
    const double overlap = reach - safe_dist2 * inv_dist;
    const double arm_i = ri[p] - 0.5 * overlap;
    const double arm_j = rj[p] - 0.5 * overlap;
    // v_rel = (v_i - v_j) + (arm_i w_i + arm_j w_j) x n.
    double vr[D];
    if constexpr (D == 3) {
      double a[3];
      for (int k = 0; k < 3; ++k) a[k] = arm_i * wi[k][p] + arm_j * wj[k][p];
      vr[0] = v[0][p] + (a[1] * n[2] - a[2] * n[1]);
      vr[1] = v[1][p] + (a[2] * n[0] - a[0] * n[2]);
      vr[2] = v[2][p] + (a[0] * n[1] - a[1] * n[0]);
    } else {
      const double a = arm_i * wi[0][p] + arm_j * wj[0][p];
      vr[0] = v[0][p] - a * n[1];
      vr[1] = v[1][p] + a * n[0];
    }
    double vn = 0.0;
    for (int k = 0; k < D; ++k) vn += vr[k] * n[k];
    double fn = p_kn * overlap + p_cn * sqrt_m * vn;
    fn = fn > 0.0 ? fn : 0.0;
    double vt[D];
    for (int k = 0; k < D; ++k) vt[k] = vr[k] - vn * n[k];

    // History: into the contact plane, length kept, then the slip of this step.
    double hh[D];
    double before = 0.0;
    double hn = 0.0;
    for (int k = 0; k < D; ++k) {
      hh[k] = h[k][p];
      before += hh[k] * hh[k];
      hn += hh[k] * n[k];
    }
    double after = 0.0;
    for (int k = 0; k < D; ++k) {
      hh[k] -= hn * n[k];
      after += hh[k] * hh[k];
    }
    const bool rescale = (before > 0.0) & (after > 0.0);
    const double scale = std::sqrt((rescale ? before : 1.0) / (rescale ? after : 1.0));
    for (int k = 0; k < D; ++k) hh[k] = hh[k] * scale + vt[k] * dt;

    // Stage 1 ends here: what stage 2 needs is kept per pair. Two loops
    // rather than one: each iteration of one loop is a long chain of
    // dependent square roots and divisions, and the processor overlaps
    // more pairs when the chain is cut in two.
    for (int k = 0; k < D; ++k) {
      s_n[k][p] = n[k];
      s_vt[k][p] = vt[k];
      s_h[k][p] = hh[k];
    }
    s_fn[p] = fn;
    s_sqrt_m[p] = sqrt_m;
    s_arm_i[p] = arm_i;
    s_arm_j[p] = arm_j;
    s_on[p] = touch ? 1.0 : 0.0;
  }
#pragma GCC ivdep
  for (int p = 0; p < count; ++p) {
    const double p_kt = Uniform ? u_kt : kt[p];
    const double p_ct = Uniform ? u_ct : ct[p];
    const double p_inv_kt = Uniform ? u_inv_kt : inv_kt[p];
    const double p_mu = Uniform ? u_mu : mu[p];
    const double sqrt_m = s_sqrt_m[p];
    const double fn = s_fn[p];
    const double arm_i = s_arm_i[p];
    const double arm_j = s_arm_j[p];
    const bool touch = s_on[p] != 0.0;
    double n[D];
    double vt[D];
    double hh[D];
    for (int k = 0; k < D; ++k) {
      n[k] = s_n[k][p];
      vt[k] = s_vt[k][p];
      hh[k] = s_h[k][p];
    }
    // Tangential spring-dashpot with the Coulomb limit.
    const double c_t = p_ct * sqrt_m;
    double ft[D];
    double ft2 = 0.0;
    for (int k = 0; k < D; ++k) {
      ft[k] = -p_kt * hh[k] - c_t * vt[k];
      ft2 += ft[k] * ft[k];
    }
    const double ft_max = p_mu * fn;
    const bool sliding = ft2 > ft_max * ft_max;
    const double limit = std::sqrt((sliding ? ft_max * ft_max : 1.0) / (sliding ? ft2 : 1.0));
    const double s = sliding ? limit : 1.0;
    // Results of pairs that do not touch are multiplied by 0 rather than
    // selected: a select makes GCC emit masked stores, which are slow on
    // AMD processors; every value here is finite (the safe inputs above).
    const double on = touch ? 1.0 : 0.0;
    const double keep = (touch & (ft_max > 0.0)) ? 1.0 : 0.0;
    for (int k = 0; k < D; ++k) {
      ft[k] *= s;
      const double slipped = -(ft[k] + c_t * vt[k]) * p_inv_kt;
      h_new[k][p] = keep * (sliding ? slipped : hh[k]);
      f[k][p] = on * (-fn * n[k] + ft[k]);
    }
    // Torques: arm x F_t with arms along n.
    if constexpr (D == 3) {
      const double c[3] = {n[1] * ft[2] - n[2] * ft[1], n[2] * ft[0] - n[0] * ft[2],
                           n[0] * ft[1] - n[1] * ft[0]};
      for (int k = 0; k < 3; ++k) {
        ti[k][p] = on * arm_i * c[k];
        tj[k][p] = on * arm_j * c[k];
      }
    } else {
      const double c = n[0] * ft[1] - n[1] * ft[0];
      ti[0][p] = on * arm_i * c;
      tj[0][p] = on * arm_j * c;
    }
  }
}

}  // namespace darcydem
