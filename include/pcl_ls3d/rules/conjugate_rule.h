#pragma once
/// \file conjugate_rule.h
/// \brief The conjugate-point rule strategy (Zuo et al. 2012, §2.2): given a transformed source
///        point and the target surface, return 0–3 observations — a unit direction u, the signed
///        distance l = uᵀ(x' − q) and the conjugate (foot) point q — or "no correspondence".
///        The engine turns each into the row a = uᵀ ∂x'/∂X of the design matrix.
///
/// Writing a new rule: derive from ConjugateRule, implement name() and findConjugate(), and
/// hand a shared pointer to LeastSquaresSurfaceMatching::setConjugateRule(). Nothing else.

#include <pcl_ls3d/rules/target_surface.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace pcl_ls3d {

/// \brief One observation l with its gradient u = ∂l/∂x' (the engine forms a = uᵀ ∂x'/∂X).
///        Distance rules: u is the unit direction and l = uᵀ(x' − q). LZD measures along z but
///        its gradient is (−∂z/∂x, −∂z/∂y, 1), because moving x' over a slope changes l.
struct ConjugateObservation
{
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< u = ∂l/∂x' (target coordinates)
  double distance = 0.0;                                 ///< signed l = uᵀ(x' − q)
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();        ///< conjugate point q on the target
  /// Variance of the local target surface at q along u (from the rule's local fit); NaN when
  /// the rule does not estimate it. Deformation detection uses it for the residuals' σ.
  double variance = std::numeric_limits<double>::quiet_NaN();
};

/// \brief Up to three observations of one source point (fixed capacity, no allocation).
struct ConjugateObservations
{
  std::array<ConjugateObservation, 3> items;
  int count = 0;

  void
  clear()
  {
    count = 0;
  }
  /// Appends one observation (ignored beyond three).
  void
  add(const Eigen::Vector3d& direction, double distance, const Eigen::Vector3d& foot,
      double variance = std::numeric_limits<double>::quiet_NaN())
  {
    if (count < 3)
      items[static_cast<std::size_t>(count++)] = {direction, distance, foot, variance};
  }
};

/// \brief Per-source-point memory a rule may keep between iterations (e.g. the local surface
///        element last used, so a point that has barely moved needs no neighbour search). The
///        engine resets it at the start of every alignment and sets `frozen` near the end.
struct CorrespondenceCache
{
  std::array<std::int32_t, 3> vertices{{-1, -1, -1}};  ///< e.g. a TIN triangle (−1: none)
  std::array<float, 6> plane{{0, 0, 0, 0, 0, 0}};      ///< e.g. a local plane: normal, point
  std::array<float, 3> anchor{{0, 0, 0}};              ///< query position the element was built for
  float reuse_radius = 0.f;                            ///< reuse the element while the query stays this close
  float variance = std::numeric_limits<float>::quiet_NaN();  ///< the element's surface variance
  std::int32_t nearest_sample = -1;  ///< the target sample nearest to `anchor` (−1: none)
  float snap_radius = 0.f;           ///< within this of nearest_sample the surface meets it
  /// Set by the engine once the estimate has settled: a rule should then reuse exactly what it
  /// cached (and give no correspondence where it cached none), so the observation set and its
  /// surface elements stay fixed and the iteration converges instead of cycling.
  bool frozen = false;
};

/// \brief Strategy interface for conjugate-point rules. Implementations must be thread-safe in
///        findConjugate() (it is called from OpenMP threads; keep scratch space thread_local).
class ConjugateRule
{
public:
  using Ptr = std::shared_ptr<ConjugateRule>;
  using ConstPtr = std::shared_ptr<const ConjugateRule>;

  virtual ~ConjugateRule() = default;

  /// Short name for reports ("LND", "LZD", "ICP", ...).
  virtual std::string
  name() const = 0;

  /// Most observations findConjugate() can return for one point (1 for LND/LZD, 3 for ICP).
  virtual int
  maxObservations() const
  {
    return 1;
  }

  /// Called once per alignment before the first iteration (build caches on the target here).
  virtual bool
  prepare(const TargetSurface& target, std::string* why)
  {
    return true;
  }

  /// Conjugate observations of `query` (a transformed source point, target coordinates).
  /// \param[in] max_distance reject correspondences farther than this
  /// \param[in,out] cache this source point's memory from the previous iteration
  /// \param[out] out observations; return false (or leave out.count == 0) for none
  virtual bool
  findConjugate(const Eigen::Vector3d& query, const TargetSurface& target, double max_distance,
                CorrespondenceCache& cache, ConjugateObservations& out) const = 0;
};

/// The rules shipped with the library.
enum class ConjugateRuleType
{
  LND,  ///< least normal distance: foot point on the local TIN triangle, u = triangle normal
  LZD,  ///< least z-difference: vertical intersection with the XY triangle, u = z
  ICP   ///< closest target point, three observations along the axes
};

/// Creates one of the shipped rules.
ConjugateRule::Ptr
makeConjugateRule(ConjugateRuleType type);

/// Parses "lnd", "lzd", "icp" (case-insensitive); false when unknown.
bool
parseConjugateRuleType(const std::string& text, ConjugateRuleType& type);

}  // namespace pcl_ls3d
