#pragma once
/// \file strip_adjustment_report.h
/// \brief Everything a strip block adjustment produced, as one plain struct: per strip the
///        correction with honest σ and the undeterminable flags, per overlap the observations
///        and the discrepancies before and after, the iteration log, the datum notes.

#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/strips/block_solve.h>
#include <pcl_ls3d/strips/discrepancies.h>

#include <array>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief A parameter the model held out (the scale of a rigid model), as it would be if freed:
///        the score test of model_adequacy.h for one strip.
struct HeldOutParameter
{
  int parameter = SCALE;      ///< 0..6 (tx ty tz φ ω κ m)
  double estimate = 0.0;      ///< the change it would take (for m: m − 1)
  double sigma = 0.0;         ///< its σ, with the sandwich's variance (at least sigma_formal)
  double sigma_formal = 0.0;  ///< σ0 √(K⁻¹)_ii
  double z = 0.0;             ///< estimate / sigma
  double effect = 0.0;        ///< what it moves the strip's edge by: |estimate| × radius (angles, m)
  double noise = 0.0;         ///< the strip's own noise: median σMAD over its evaluated overlaps
  bool significant = false;   ///< |z| > settings.held_out_z
  bool flagged = false;       ///< significant and effect > settings.held_out_noise_factor × noise
};

/// \brief The block's test of the held-out parameters (model_adequacy.h).
struct HeldOutTest
{
  bool tested = false;
  std::string note;                  ///< why not tested, or what was tested
  double statistic = 0.0;            ///< all strips' held-out parameters together: χ² under a right model
  int dof = 0;                       ///< its degrees of freedom
  int significant = 0, flagged = 0;  ///< strips
};

/// \brief One strip's result. Parameters act about the strip's origin: x' = o + t + m R (x − o).
struct StripResult
{
  std::string name;
  int point_source_id = -1;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< o in file coordinates
  std::size_t points = 0, observable = 0;
  ExclusionCounts excluded;
  bool reference = false;  ///< fixed datum strip
  bool adjusted = false;   ///< has a used overlap (else left unchanged)
  Vector7d parameters = identityParameters();
  Vector7d sigmas = Vector7d::Zero();         ///< √C_ii (0 fixed, +inf undeterminable)
  Vector7d sigmas_formal = Vector7d::Zero();  ///< σ0 √q_ii (eq. 14)
  std::array<bool, 7> fixed{}, determinable{};
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();  ///< file coordinates
  std::string note;
  std::vector<HeldOutParameter> held_out;  ///< empty when not tested (reference, 7 parameters)
};

/// \brief One overlap's result.
struct OverlapResult
{
  int i = -1, j = -1;
  double area = 0.0;
  std::size_t common_cells = 0, points_i = 0, points_j = 0;
  bool used = false;
  std::string skip_reason;
  double spacing = 0.0;                                 ///< thinning cell edge
  std::size_t observations = 0, used_observations = 0;  ///< final pass, both directions
  double sigma0 = 0.0;                                  ///< √(Σ p v² / used) in the final pass
  /// √(Σ p σ²_surface / used): the conjugate surfaces' own σ at the query points (LND: the
  /// local quadric's height σ). For points with noise σ_n, E[σ0²] ≈ σ_n² + sigma_surface².
  double sigma_surface = 0.0;
  DiscrepancyStatistics before, after;
  DiscrepancyStatistics noise_i, noise_j;  ///< the strips' own noise on the same surfaces
  /// The translation of i against j that the discrepancies after adjustment still ask for
  /// (values within kAskedWithinNoise × the larger own noise): ~0 at a least-squares solution
  /// of LND's distances, which the discrepancies are.
  AskedTranslation asked;
};

/// Discrepancies beyond this multiple of the strips' own noise (walls, edges seen from two
/// sides) are left out of OverlapResult::asked.
constexpr double kAskedWithinNoise = 5.0;

/// \brief The block adjustment's report.
struct StripAdjustmentReport
{
  TerminationType termination = TerminationType::NOT_RUN;
  std::string message;
  int iterations = 0;
  double sigma0 = 0.0;
  long redundancy = 0;
  std::size_t observations = 0;  ///< with weight > 0 in the last solve
  int unknowns = 0;              ///< estimated parameters
  std::string rule, estimator, model, precision_model;
  Eigen::Vector3d block_origin = Eigen::Vector3d::Zero();  ///< file = block + this
  double footprint_cell = 0.0;
  std::vector<StripResult> strips;
  std::vector<OverlapResult> overlaps;
  std::vector<BlockIterationRecord> log;
  std::vector<std::string> notes;
  HeldOutTest held_out;           ///< is the model large enough?
  Eigen::MatrixXd covariance;     ///< 7N × 7N behind the σ
  std::vector<double> timings_s;  ///< plan, select, iterate, evaluate

  bool
  converged() const
  {
    return termination == TerminationType::CONVERGED;
  }
};

}  // namespace strips
}  // namespace pcl_ls3d
