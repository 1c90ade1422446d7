/// \file reference_objects.cpp
/// \brief Reference objects from a classification (connected components per class group) or
///        from generator ids.

#include <pcl_ls3d/evaluation/reference_objects.h>
#include <pcl_ls3d/stats/descriptive.h>

#include <pcl/search/kdtree.h>

#include <algorithm>
#include <map>

namespace pcl_ls3d {
namespace evaluation {
namespace {

/// max(1, 2.5 × median distance to the nearest other point), from up to 20 000 sampled points.
double
automaticRadius(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
                pcl::search::KdTree<pcl::PointXYZ>& tree)
{
  const std::size_t step = std::max<std::size_t>(1, cloud->size() / 20000);
  std::vector<double> nn;
  pcl::Indices idx;
  std::vector<float> d2;
  for (std::size_t i = 0; i < cloud->size(); i += step)
    if (tree.nearestKSearch((*cloud)[i], 2, idx, d2) == 2)
      nn.push_back(std::sqrt(static_cast<double>(d2[1])));
  const double m = stats::median(nn);
  return std::isfinite(m) ? std::max(1.0, 2.5 * m) : 1.0;
}

}  // namespace

bool
referenceObjectsFromLabels(const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<int>& labels,
                           const ReferenceObjectSettings& settings, ReferenceObjects& objects,
                           std::string& error)
{
  if (cloud.size() != labels.size() || cloud.empty()) {
    error = "reference objects need one label per point of a non-empty cloud (" +
            std::to_string(labels.size()) + " labels, " + std::to_string(cloud.size()) + " points)";
    return false;
  }
  ReferenceObjects out;
  for (const auto& g : settings.groups)
    out.group_names.push_back(g.name);
  const ClassLookup lookup(settings.groups, settings.excluded_codes);
  const std::size_t n = cloud.size();
  // Points of every evaluated code are connected to points of the same group; "other" codes
  // connect per code (a bridge and a water surface are different things).
  std::vector<int> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int g = lookup.groupOf(labels[i]);
    key[i] = g == ClassLookup::kExcluded ? -1 : g >= 0 ? g : 1000 + labels[i];
  }
  // Plan-connected groups are searched with z flattened; joins need equal keys, so the
  // flattened points never connect to another group.
  std::vector<char> in_plan(settings.groups.size(), 0);
  for (std::size_t g = 0; g < settings.groups.size(); ++g)
    in_plan[g] = std::find(settings.plan_connected_groups.begin(), settings.plan_connected_groups.end(),
                           settings.groups[g].name) != settings.plan_connected_groups.end();
  pcl::PointCloud<pcl::PointXYZ>::Ptr all(new pcl::PointCloud<pcl::PointXYZ>(cloud));
  pcl::search::KdTree<pcl::PointXYZ> tree;
  tree.setInputCloud(all);
  out.radius = settings.radius > 0.0 ? settings.radius : automaticRadius(all, tree);
  bool flattened = false;
  for (std::size_t i = 0; i < n; ++i)
    if (key[i] >= 0 && key[i] < 1000 && in_plan[static_cast<std::size_t>(key[i])]) {
      (*all)[i].z = 0.f;
      flattened = true;
    }
  if (flattened)
    tree.setInputCloud(all);

  out.object_of.assign(n, ReferenceObjects::kUnlabelled);
  std::vector<int> queue;
  pcl::Indices nn;
  std::vector<float> d2;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (key[seed] < 0 || out.object_of[seed] != ReferenceObjects::kUnlabelled)
      continue;
    const int id = static_cast<int>(out.size.size());
    out.object_of[seed] = id;
    queue.assign(1, static_cast<int>(seed));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      tree.radiusSearch((*all)[queue[q]], out.radius, nn, d2);
      for (const auto j : nn)
        if (key[j] == key[seed] && out.object_of[j] == ReferenceObjects::kUnlabelled) {
          out.object_of[j] = id;
          queue.push_back(j);
        }
    }
    out.size.push_back(queue.size());
    out.group_of_object.push_back(key[seed] < 1000 ? key[seed] : ClassLookup::kOther);
  }
  objects = std::move(out);
  return true;
}

bool
referenceObjectsFromIds(const std::vector<int>& ids, const std::vector<int>& labels,
                        const std::vector<ClassGroup>& groups, const std::vector<int>& excluded_codes,
                        ReferenceObjects& objects, std::string& error)
{
  if (ids.size() != labels.size()) {
    error = "reference objects need one id per label (" + std::to_string(ids.size()) + " ids, " +
            std::to_string(labels.size()) + " labels)";
    return false;
  }
  ReferenceObjects out;
  for (const auto& g : groups)
    out.group_names.push_back(g.name);
  const ClassLookup lookup(groups, excluded_codes);
  std::map<int, int> dense;
  std::vector<std::map<int, std::size_t>> votes;  // per object: group (other = G) -> points
  out.object_of.assign(ids.size(), ReferenceObjects::kUnlabelled);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const int g = lookup.groupOf(labels[i]);
    if (ids[i] < 0 || g == ClassLookup::kExcluded)
      continue;
    const auto it = dense.emplace(ids[i], static_cast<int>(dense.size())).first;
    if (it->second == static_cast<int>(votes.size()))
      votes.emplace_back();
    out.object_of[i] = it->second;
    ++votes[static_cast<std::size_t>(it->second)][g];
  }
  for (const auto& v : votes) {
    std::size_t total = 0, best = 0;
    int best_group = ClassLookup::kOther;
    for (const auto& [g, count] : v) {
      total += count;
      if (count > best || (count == best && g >= 0 && best_group < 0)) {
        best = count;
        best_group = g;
      }
    }
    out.size.push_back(total);
    out.group_of_object.push_back(best_group);
  }
  objects = std::move(out);
  return true;
}

}  // namespace evaluation
}  // namespace pcl_ls3d
