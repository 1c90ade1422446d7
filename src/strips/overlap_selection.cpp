#include <pcl_ls3d/stats/descriptive.h>
#include <pcl_ls3d/strips/overlap_selection.h>

#include <pcl/kdtree/kdtree_flann.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace pcl_ls3d {
namespace strips {

namespace {

using CellSet = std::unordered_set<std::uint64_t>;

// The common cells grown by `radius` cells (the target must cover where the observed points
// go while the strips are still apart).
CellSet
dilate(const std::vector<std::uint64_t>& cells, const maps::GridGeometry& g, int radius)
{
  CellSet out;
  out.reserve(cells.size() * static_cast<std::size_t>((2 * radius + 1) * (2 * radius + 1)) / 2);
  for (std::uint64_t id : cells) {
    const long row = static_cast<long>(id / static_cast<std::uint64_t>(g.cols));
    const long col = static_cast<long>(id % static_cast<std::uint64_t>(g.cols));
    for (long r = std::max(0L, row - radius); r <= std::min<long>(g.rows - 1, row + radius); ++r)
      for (long c = std::max(0L, col - radius); c <= std::min<long>(g.cols - 1, col + radius); ++c)
        out.insert(static_cast<std::uint64_t>(r) * static_cast<std::uint64_t>(g.cols) +
                   static_cast<std::uint64_t>(c));
  }
  return out;
}

// RMS distance of each region point's 10 nearest neighbours (itself included) to their plane.
std::vector<double>
roughness(const Strip& s, const std::vector<std::size_t>& region)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(region.size());
  for (std::size_t k = 0; k < region.size(); ++k)
    (*cloud)[k].getVector3fMap() = s.points[region[k]];
  std::vector<double> rms(region.size(), std::numeric_limits<double>::infinity());
  if (region.size() < 10)
    return rms;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
#pragma omp parallel
  {
    pcl::Indices nn;
    std::vector<float> d2;
#pragma omp for schedule(dynamic, 1024)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(region.size()); ++k) {
      if (tree.nearestKSearch((*cloud)[static_cast<std::size_t>(k)], 10, nn, d2) < 10)
        continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int q : nn)
        mean += (*cloud)[static_cast<std::size_t>(q)].getVector3fMap().cast<double>();
      mean /= 10.0;
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (int q : nn) {
        const Eigen::Vector3d d =
            (*cloud)[static_cast<std::size_t>(q)].getVector3fMap().cast<double>() - mean;
        cov += d * d.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov / 10.0, Eigen::EigenvaluesOnly);
      rms[static_cast<std::size_t>(k)] = std::sqrt(std::max(0.0, eig.eigenvalues()[0]));
    }
  }
  return rms;
}

struct StripPart
{
  std::vector<std::size_t> region;      // observable points in the grown common cells
  std::vector<std::uint8_t> stable;     // per region point
  std::vector<std::size_t> candidates;  // stable region points inside the common cells
};

StripPart
partOf(const std::vector<Strip>& strips, int k, const CellSet& common, const CellSet& grown,
       const Footprints& f, const StripAdjustmentSettings& settings)
{
  const Strip& s = strips[static_cast<std::size_t>(k)];
  StripPart part;
  std::vector<std::uint8_t> in_common;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.observable[i])
      continue;
    const Eigen::Vector3d b = s.blockPoint(i);
    const std::int64_t id = f.cellId(b.x(), b.y());
    if (id < 0 || !grown.count(static_cast<std::uint64_t>(id)))
      continue;
    part.region.push_back(i);
    in_common.push_back(common.count(static_cast<std::uint64_t>(id)) ? 1 : 0);
  }
  part.stable = stableFlags(s, part.region, settings);
  for (std::size_t r = 0; r < part.region.size(); ++r)
    if (part.stable[r] && in_common[r])
      part.candidates.push_back(part.region[r]);
  return part;
}

void
fillDirection(const std::vector<Strip>& strips, int source, int target, const StripPart& src,
              const StripPart& tgt, double spacing, DirectionSelection& d)
{
  const Strip& s = strips[static_cast<std::size_t>(source)];
  const Strip& t = strips[static_cast<std::size_t>(target)];
  d.source = source;
  d.target = target;
  d.candidates = src.candidates.size();
  std::vector<Eigen::Vector2d> xy(src.candidates.size());
  for (std::size_t k = 0; k < xy.size(); ++k)
    xy[k] = s.blockPoint(src.candidates[k]).head<2>();
  for (std::size_t k : thinRegularly(xy, spacing)) {
    d.points.push_back(s.points[src.candidates[k]].cast<double>());
    d.indices.push_back(static_cast<std::uint32_t>(src.candidates[k]));
  }
  d.surface.reset(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t r = 0; r < tgt.region.size(); ++r)
    if (tgt.stable[r]) {
      pcl::PointXYZ p;
      p.getVector3fMap() = t.points[tgt.region[r]];
      d.surface->push_back(p);
    }
}

}  // namespace

std::vector<std::size_t>
thinRegularly(const std::vector<Eigen::Vector2d>& xy, double spacing)
{
  std::vector<std::size_t> out;
  if (!(spacing > 0.0)) {
    out.resize(xy.size());
    for (std::size_t k = 0; k < xy.size(); ++k)
      out[k] = k;
    return out;
  }
  struct Best
  {
    std::size_t index;
    double d2;
  };
  std::unordered_map<std::uint64_t, Best> best;
  best.reserve(xy.size() / 2);
  for (std::size_t k = 0; k < xy.size(); ++k) {
    const double fx = std::floor(xy[k].x() / spacing), fy = std::floor(xy[k].y() / spacing);
    const double dx = xy[k].x() - (fx + 0.5) * spacing, dy = xy[k].y() - (fy + 0.5) * spacing;
    const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::int64_t>(fy) & 0xFFFFFFFF) << 32) |
                              (static_cast<std::uint64_t>(static_cast<std::int64_t>(fx)) & 0xFFFFFFFF);
    const double d2 = dx * dx + dy * dy;
    auto it = best.find(key);
    if (it == best.end())
      best.emplace(key, Best{k, d2});
    else if (d2 < it->second.d2)
      it->second = Best{k, d2};
  }
  out.reserve(best.size());
  for (const auto& kv : best)
    out.push_back(kv.second.index);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::uint8_t>
stableFlags(const Strip& strip, const std::vector<std::size_t>& region,
            const StripAdjustmentSettings& settings)
{
  std::vector<std::uint8_t> flags(region.size(), 0);
  if (strip.classified()) {
    for (std::size_t r = 0; r < region.size(); ++r)
      flags[r] = settings.stable_classes.count(strip.classification[region[r]]) ? 1 : 0;
    return flags;
  }
  const std::vector<double> rms = roughness(strip, region);
  std::vector<double> finite;
  for (double v : rms)
    if (std::isfinite(v))
      finite.push_back(v);
  const double limit = settings.roughness_factor * stats::median(finite);
  for (std::size_t r = 0; r < region.size(); ++r)
    flags[r] = rms[r] <= limit ? 1 : 0;
  return flags;
}

OverlapSelection
selectObservations(const std::vector<Strip>& strips, const Overlap& o, const Footprints& f,
                   const StripAdjustmentSettings& settings)
{
  OverlapSelection sel;
  const CellSet common(o.cells.begin(), o.cells.end());
  const int radius =
      static_cast<int>(std::ceil(std::min(settings.max_distance, 8.0 * f.cell()) / f.cell())) + 1;
  const CellSet grown = dilate(o.cells, f.grid(), radius);
  const StripPart a = partOf(strips, o.i, common, grown, f, settings);
  const StripPart b = partOf(strips, o.j, common, grown, f, settings);
  // Thinning: 2 × the point spacing of the sparser strip, widened so that the common area
  // gives at most max_observations per direction.
  const double di = f.density(static_cast<std::size_t>(o.i)), dj = f.density(static_cast<std::size_t>(o.j));
  const double base = 2.0 / std::sqrt(std::max(1e-12, std::min(di, dj)));
  sel.spacing = settings.observation_spacing > 0.0
                    ? settings.observation_spacing
                    : std::max(base, std::sqrt(o.area / static_cast<double>(settings.max_observations)));
  fillDirection(strips, o.i, o.j, a, b, sel.spacing, sel.forward);
  fillDirection(strips, o.j, o.i, b, a, sel.spacing, sel.backward);
  return sel;
}

}  // namespace strips
}  // namespace pcl_ls3d
