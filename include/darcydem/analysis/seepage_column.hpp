#pragma once
// [analysis] kind = "seepage_column": the paper's verification, run alongside
// the stages. It measures the column in the settling stage (settlement, the
// m_v it implies, the settled porosity and permeability), records the uplift
// and the pore-pressure profiles during the inflow stage, compares them with
// the closed form (seepage_analytic.hpp) using the measured parameters, and
// writes uplift.csv, pressure.csv, the analytical curves, report.md,
// seepage.json and, with matplotlib, uplift.png and pressure.png.
#include <iosfwd>
#include <string>
#include <vector>

#include "darcydem/analysis/seepage_analytic.hpp"
#include "darcydem/scene/scene.hpp"

namespace darcydem {

struct SeepageColumnResult {
  double settlement = 0.0;        ///< m, in the settling stage
  double initial_porosity = 0.0;  ///< -
  double settled_porosity = 0.0;  ///< -
  double kozeny_carman_conductivity =
      0.0;                              ///< k from Eq. 15 at the settled porosity, m/s (0: constant model)
  SeepageColumnParameters parameters;   ///< as measured (with the fluid storage n/K_f)
  double uplift_rms_error = 0.0;        ///< RMS(S_sim - S_analytic) / final uplift over 0..1 s
  double pressure_max_error = 0.0;      ///< max |u_sim - u_analytic| / steady bottom pressure
  double final_uplift_simulated = 0.0;  ///< m, at the last sample
  bool complete = false;                ///< both stages ran to the end
  bool passed = false;                  ///< complete and both errors within tolerance
};

template <int D>
class SeepageColumnAnalysis {
 public:
  SeepageColumnAnalysis(SeepageColumnSpec spec, const Scene<D>& scene);
  void stage_started(const Scene<D>& scene, const std::string& stage);
  void stage_ended(const Scene<D>& scene, const std::string& stage, bool completed);
  void after_step(const Scene<D>& scene);
  /// Computes the comparison and writes the files into out_dir.
  SeepageColumnResult finish(const Scene<D>& scene, const std::string& out_dir, std::ostream* log);
  /// What it has measured and recorded so far (the spec comes from the scene).
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(base_, top_, area_, solid_volume_, top_initial_, top_settled_, settle_done_, inflow_active_,
       inflow_done_, t0_, top_at_inflow_, inflow_, next_sample_, kappa_effective_, next_profile_,
       sample_time_, sample_uplift_, profiles_);
  }

 private:
  [[nodiscard]] double column_top(const Scene<D>& scene) const;

  struct Profile {
    double nominal_time, actual_time;
    std::vector<double> depth, pressure;
    template <class Archive>
    void checkpoint(Archive& ar) {
      ar(nominal_time, actual_time, depth, pressure);
    }
  };
  SeepageColumnSpec spec_;
  double base_ = 0.0, top_ = 0.0, area_ = 0.0, solid_volume_ = 0.0;
  double top_initial_ = 0.0, top_settled_ = 0.0;
  bool settle_done_ = false, inflow_active_ = false, inflow_done_ = false;
  double t0_ = 0.0, top_at_inflow_ = 0.0, inflow_ = 0.0, next_sample_ = 0.0;
  double kappa_effective_ =
      0.0;  ///< series (harmonic) mean of the layers' vertical kappa at the inflow start
  std::size_t next_profile_ = 0;
  std::vector<double> sample_time_, sample_uplift_;
  std::vector<Profile> profiles_;
};

}  // namespace darcydem
