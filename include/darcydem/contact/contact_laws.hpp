#pragma once
// Normal contact laws as small value types, and the per-material-pair table.
// Each law gives, for an overlap d > 0 and approach speed vn (> 0 closing),
// the normal force magnitude and the stiffnesses the tangential and rolling
// parts need. The loop over contacts is written once (contact_kernel.hpp),
// templated on the law, which is chosen once per run.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "darcydem/contact/material.hpp"

namespace darcydem {

/// Per material pair: everything a contact evaluation needs.
struct PairParameters {
  NormalLaw law = NormalLaw::linear;
  double normal_stiffness = 0.0;    ///< N/m (linear)
  double tangential_ratio = 1.0;    ///< k_t / k_n (linear)
  double hertz_modulus = 0.0;       ///< E* = 1 / ((1-nu1^2)/E1 + (1-nu2^2)/E2), Pa
  double shear_modulus = 0.0;       ///< G* = 1 / ((2-nu1)/G1 + (2-nu2)/G2), Pa
  double normal_damping = 0.0;      ///< dimensionless gamma (restitution.hpp)
  double tangential_damping = 0.0;  ///< dimensionless, c_t = gamma_t sqrt(m k_t)
  double friction = 0.0;            ///< Coulomb mu
  double rolling_friction = 0.0;    ///< mu_r (0: no rolling resistance)
  /// Contact bond (linear law only): the largest tension and tangential
  /// force a bonded pair carries before the bond breaks, N.
  bool bondable = false;
  double bond_tensile = 0.0;
  double bond_shear = 0.0;
  /// A bond's moment (0: a pin): stiffness ratios (k = ratio k_n R*^2) and
  /// strengths, N m; twisting in 3D only.
  double bond_bending_ratio = 0.0;
  double bond_bending_strength = 0.0;
  double bond_twisting_ratio = 0.0;
  double bond_twisting_strength = 0.0;
  [[nodiscard]] bool bond_has_moment() const {
    return bondable && (bond_bending_ratio > 0.0 || bond_twisting_ratio > 0.0);
  }
  /// The rolling spring's stiffness (type C), k_r = 2.25 k_n mu_r^2 R*^2,
  /// N m/rad, from the normal spring's stiffness k_n at the contact.
  [[nodiscard]] double rolling_stiffness(double k_n, double r_eff) const {
    return 2.25 * k_n * rolling_friction * rolling_friction * r_eff * r_eff;
  }
  /// The bond's bending and twisting spring stiffnesses, ratio k_n R*^2,
  /// N m/rad, for a pair of effective radius r_eff = R_i R_j / (R_i + R_j).
  [[nodiscard]] double bond_bending_stiffness(double r_eff) const {
    return bond_bending_ratio * normal_stiffness * r_eff * r_eff;
  }
  [[nodiscard]] double bond_twisting_stiffness(double r_eff) const {
    return bond_twisting_ratio * normal_stiffness * r_eff * r_eff;
  }
  /// Strengths that vary from bond to bond: Weibull's modulus m (0: none),
  /// the scale 1 / Gamma(1 + 1/m) that makes the mean factor 1, the seed.
  double bond_weibull_modulus = 0.0;
  double bond_weibull_scale = 1.0;
  std::uint64_t bond_seed = 0;
  [[nodiscard]] bool bond_strength_varies() const { return bondable && bond_weibull_modulus > 0.0; }
  /// The factor on all the strengths of the bond between the grains of ids
  /// a and b: f = scale (-ln U)^(1/m), Weibull's distribution of mean 1,
  /// with U in (0, 1) a hash of the unordered pair and the seed, so that a
  /// bond's strength depends neither on the order of the grains in memory
  /// nor on the thread count. 1 when the strengths do not vary.
  [[nodiscard]] double bond_strength_factor(std::uint32_t a, std::uint32_t b) const {
    if (!bond_strength_varies()) return 1.0;
    const std::uint64_t lo = a < b ? a : b;
    const std::uint64_t hi = a < b ? b : a;
    const std::uint64_t h = mix_bits(mix_bits(bond_seed) ^ ((lo << 32) | hi));
    return bond_strength_quantile((static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53);
  }
  /// The factor that a fraction `exceedance` of the bonds exceed:
  /// P(f > x) = exp(-(x / scale)^m), so x = scale (-ln exceedance)^(1/m).
  /// 1 when the strengths do not vary.
  [[nodiscard]] double bond_strength_quantile(double exceedance) const {
    if (!bond_strength_varies()) return 1.0;
    return bond_weibull_scale * std::pow(-std::log(exceedance), 1.0 / bond_weibull_modulus);
  }
  /// A 64-bit finalizer (an avalanche of xor-shifts and odd multipliers).
  [[nodiscard]] static std::uint64_t mix_bits(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
  // Derived (ContactTable::set fills them): square roots the dashpots need.
  double sqrt_normal_stiffness = 0.0;      ///< sqrt(k_n), sqrt(N/m) (linear)
  double sqrt_tangential_stiffness = 0.0;  ///< sqrt(k_t), sqrt(N/m) (linear)
  double inv_tangential_stiffness = 0.0;   ///< 1/k_t, m/N (linear; 0 if k_t = 0)

  void derive() {
    const double kt = tangential_ratio * normal_stiffness;
    sqrt_normal_stiffness = std::sqrt(normal_stiffness);
    sqrt_tangential_stiffness = std::sqrt(kt);
    inv_tangential_stiffness = kt > 0.0 ? 1.0 / kt : 0.0;
  }
};

struct NormalResponse {
  double force;                      ///< N, >= 0 (repulsive)
  double normal_stiffness;           ///< N/m, tangent dF/dd
  double tangential_stiffness;       ///< N/m
  double sqrt_tangential_stiffness;  ///< sqrt(N/m), for the tangential dashpot
  double inv_tangential_stiffness;   ///< m/N (0 if the stiffness is 0)
};

/// Linear spring-dashpot: F = k_n d + gamma sqrt(m k_n) vn, clamped at 0;
/// k_t = ratio * k_n. sqrt_m is the square root of the effective mass.
struct LinearSpringDashpot {
  static NormalResponse evaluate(const PairParameters& p, double overlap, double vn, double sqrt_m,
                                 double /*r_eff*/) {
    const double k = p.normal_stiffness;
    const double f = k * overlap + p.normal_damping * sqrt_m * p.sqrt_normal_stiffness * vn;
    return {f > 0.0 ? f : 0.0, k, p.tangential_ratio * k, p.sqrt_tangential_stiffness,
            p.inv_tangential_stiffness};
  }
};

/// Hertz-Mindlin with Tsuji damping:
///   F = K d^1.5 + gamma sqrt(m K) d^0.25 vn, K = 4/3 E* sqrt(R*), clamped at 0;
///   k_n = 2 E* sqrt(R* d) (tangent), k_t = 8 G* sqrt(R* d) (Mindlin, no slip).
struct HertzMindlin {
  static NormalResponse evaluate(const PairParameters& p, double overlap, double vn, double sqrt_m,
                                 double r_eff) {
    const double a = std::sqrt(r_eff * overlap);  // contact radius
    const double big_k = 4.0 / 3.0 * p.hertz_modulus * std::sqrt(r_eff);
    const double f = big_k * overlap * std::sqrt(overlap) +
                     p.normal_damping * sqrt_m * std::sqrt(big_k) * std::sqrt(std::sqrt(overlap)) * vn;
    const double kt = 8.0 * p.shear_modulus * a;
    return {f > 0.0 ? f : 0.0, 2.0 * p.hertz_modulus * a, kt, std::sqrt(kt), kt > 0.0 ? 1.0 / kt : 0.0};
  }
};

/// Several laws in one scene: dispatch on the pair's law (well predicted).
struct MixedNormalLaw {
  static NormalResponse evaluate(const PairParameters& p, double overlap, double vn, double sqrt_m,
                                 double r_eff) {
    if (p.law == NormalLaw::linear) {
      return LinearSpringDashpot::evaluate(p, overlap, vn, sqrt_m, r_eff);
    }
    return HertzMindlin::evaluate(p, overlap, vn, sqrt_m, r_eff);
  }
};

/// Symmetric table of pair parameters over materials (walls have materials too).
class ContactTable {
 public:
  ContactTable() = default;
  explicit ContactTable(std::size_t n_materials) : n_(n_materials), pairs_(n_materials * n_materials) {}
  void set(std::size_t a, std::size_t b, PairParameters p) {
    p.derive();
    pairs_[a * n_ + b] = p;
    pairs_[b * n_ + a] = p;
  }
  [[nodiscard]] const PairParameters& operator()(std::size_t a, std::size_t b) const {
    return pairs_[a * n_ + b];
  }
  [[nodiscard]] std::size_t materials() const { return n_; }
  [[nodiscard]] const std::vector<PairParameters>& all() const { return pairs_; }
  /// A new Coulomb coefficient for the pair (a stage's `contacts`): the
  /// contacts' tangential springs are held to it from the next evaluation.
  void set_friction(std::size_t a, std::size_t b, double mu) {
    pairs_[a * n_ + b].friction = mu;
    pairs_[b * n_ + a].friction = mu;
  }
  /// Every pair's Coulomb coefficient, as a checkpoint keeps them.
  [[nodiscard]] std::vector<double> frictions() const {
    std::vector<double> mu;
    for (const auto& p : pairs_) mu.push_back(p.friction);
    return mu;
  }
  void set_frictions(const std::vector<double>& mu) {
    if (mu.size() != pairs_.size()) throw std::runtime_error("ContactTable: frictions of another scene");
    for (std::size_t k = 0; k < mu.size(); ++k) pairs_[k].friction = mu[k];
  }
  [[nodiscard]] bool any_bondable() const {
    for (const auto& p : pairs_) {
      if (p.bondable) return true;
    }
    return false;
  }
  [[nodiscard]] bool any_bond_moment() const {
    for (const auto& p : pairs_) {
      if (p.bond_has_moment()) return true;
    }
    return false;
  }
  [[nodiscard]] bool any_bond_strength_variation() const {
    for (const auto& p : pairs_) {
      if (p.bond_strength_varies()) return true;
    }
    return false;
  }
  [[nodiscard]] bool any_rolling() const {
    for (const auto& p : pairs_) {
      if (p.rolling_friction > 0.0) return true;
    }
    return false;
  }

 private:
  std::size_t n_ = 0;
  std::vector<PairParameters> pairs_;
};

/// Builds the pair parameters of two materials from the scene's contact spec,
/// calibrating the damping to the restitution.
PairParameters make_pair_parameters(const Material& a, const Material& b, const ContactSpec& spec);

}  // namespace darcydem
