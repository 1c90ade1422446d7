#pragma once
// Internal steps of SurfaceMatchingCore::run (not installed): the pair's frames and starting
// values (setUpPair, shared with LinearizedMatching in sample_consensus/), the source-noise
// estimate, the design rows and normal equations of one iteration, and the precision and
// reliability fields of the report. The overlap and degenerate-target checks live in
// rules/target_overlap.h.
#include <pcl_ls3d/adjustment/adjustment_report.h>
#include <pcl_ls3d/adjustment/adjustment_settings.h>
#include <pcl_ls3d/adjustment/errors_in_variables.h>
#include <pcl_ls3d/adjustment/gauss_markov.h>
#include <pcl_ls3d/adjustment/normal_equations.h>
#include <pcl_ls3d/adjustment/omitted_parameters.h>
#include <pcl_ls3d/adjustment/pair_matcher.h>
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace detail {

/// Stage 1 for a pair: the source block (o_s → o_t, starting values, a-priori observations),
/// the target block (fixed identity about o_t) and what later stages need to know of the data.
struct PairSetup
{
  ParameterBlock source;
  ParameterBlock target;
  Eigen::AlignedBox3d target_box;  ///< of the target points (cloud coordinates)
  Eigen::AlignedBox3d source_box;  ///< of the finite reduced source points
  std::vector<int> inside;         ///< source points over the target's box (σ_s seeds)
  double radius = 0.0;             ///< largest |finite reduced source point|
};

/// Reduction to a local origin near the overlap (conditioning on georeferenced data), starting
/// values from the guess (eq. 9; fixed parameters start exactly at L_e), and the reduced source
/// points. False: no source point lies over the target.
bool
setUpPair(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
          const Eigen::Matrix4d& guess, const AdjustmentSettings& settings, PairSetup& setup,
          std::vector<Eigen::Vector3d>& reduced);

/// σ_s of the source from its own roughness around the points over the target (~30 neighbours
/// each), for the errors-in-variables correction; 0 when it cannot be estimated.
double
sourceNoise(const std::vector<Eigen::Vector3d>& reduced, const PairSetup& setup);

/// Cell edge of the spatial precision estimator: settings.precision_cell, or 8 × the target's
/// mean XY spacing; 0 when neither is known.
double
precisionCell(const AdjustmentSettings& settings, const PairSetup& setup, std::size_t target_size);

/// σ_i (√C_ii of report.covariance; 0 fixed, +inf undeterminable), formal σ0 √q_ii and the
/// correlation from C; returns the names of the undeterminable parameters.
std::string
fillPrecision(AdjustmentReport& report, const GaussMarkovSolution& sol);

/// Up to `most` conjugate points spread over an observation set (target coordinates), e.g. as
/// seeds of the target's noise estimate.
std::vector<Eigen::Vector3d>
conjugatePoints(const ObservationSet& set, std::size_t most = 256);

/// The 7 flags of a one-block solution as the report's array.
std::array<bool, 7>
flags7(const std::vector<bool>& flags);

/// Design row of the source block with the errors-in-variables correction of the scale column
/// (errors_in_variables.h): a_m' = a_m − c l.
struct SourceRows
{
  const PairMatcher& matcher;
  const ObservationSet& set;
  const ScaleColumnCorrection& eiv;

  RowVector7d
  operator()(std::size_t j) const
  {
    return of(set[j]);
  }
  RowVector7d
  of(const Observation& o) const
  {
    RowVector7d a = matcher.sourceRow(o);
    a[SCALE] -= eiv.coefficient(o.direction.squaredNorm()) * o.distance;
    return a;
  }
};

/// Eq. 8: AᵀPA, AᵀPL over the observations with weights p (in [0, 1]).
NormalEquations
accumulateNormalEquations(const SourceRows& row, const Eigen::VectorXd& weights);

/// Mean |u|² of the observations (1 for unit directions), for the errors-in-variables term.
double
meanSquaredGradient(const ObservationSet& set);

/// The log line of one iteration.
IterationRecord
iterationRecord(int it, const NormalEquations& ne, std::size_t m, const GaussMarkovSolution& sol);

/// Precision: formal σ0² Qxx (eq. 14), replaced by the spatial sandwich (spatial_precision.h)
/// when there is redundancy and a cell, from the last iteration's observation set.
void
fillCovariance(AdjustmentReport& report, const GaussMarkovSolution& sol, const SourceRows& row,
               const Eigen::VectorXd& weights, const Vector7d& apriori_weights, double cell);

/// The score test of a rigid fit's held-out scale (omitted_parameters.h) from the last
/// iteration's observations at the updated estimate, with the variance of fillCovariance()
/// (the spatial middle term at this cell, formal at cell 0). Not ok when the scale was
/// estimated or other parameters were held too.
OmittedParameterTest
heldOutScaleTest(const GaussMarkovSolution& sol, const SourceRows& row, const Eigen::VectorXd& weights,
                 const GaussMarkovProblem& problem, double cell);

/// Reliability: residuals (eq. 12) and redundancy numbers r_i = 1 − p_i a_iᵀ Qxx a_i.
void
storeObservations(AdjustmentReport& report, const GaussMarkovSolution& sol, const SourceRows& row,
                  const Eigen::VectorXd& weights, const std::vector<int>& source_indices);

}  // namespace detail
}  // namespace pcl_ls3d
