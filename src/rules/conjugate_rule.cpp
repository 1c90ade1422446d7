#include <pcl_ls3d/rules/conjugate_rule.h>
#include <pcl_ls3d/rules/icp_rule.h>
#include <pcl_ls3d/rules/lnd_rule.h>
#include <pcl_ls3d/rules/lzd_rule.h>

#include <algorithm>
#include <cctype>
#include <numeric>

namespace pcl_ls3d {

ConjugateRule::Ptr
makeConjugateRule(ConjugateRuleType type)
{
  switch (type) {
  case ConjugateRuleType::LND:
    return std::make_shared<LndRule>();
  case ConjugateRuleType::LZD:
    return std::make_shared<LzdRule>();
  case ConjugateRuleType::ICP:
    return std::make_shared<IcpRule>();
  }
  return nullptr;
}

bool
parseConjugateRuleType(const std::string& text, ConjugateRuleType& type)
{
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "lnd")
    type = ConjugateRuleType::LND;
  else if (t == "lzd")
    type = ConjugateRuleType::LZD;
  else if (t == "icp")
    type = ConjugateRuleType::ICP;
  else
    return false;
  return true;
}

int
PointVectorTargetSurface::nearestKSearch(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                                         std::vector<float>& sq_dists) const
{
  // Brute force: partial sort of all points by distance (small inputs only).
  const int n = static_cast<int>(points_.size());
  k = std::min(k, n);
  if (k <= 0)
    return 0;
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  auto d2 = [&](int i) { return (points_[static_cast<std::size_t>(i)] - query).squaredNorm(); };
  std::partial_sort(all.begin(), all.begin() + k, all.end(), [&](int a, int b) { return d2(a) < d2(b); });
  indices.assign(all.begin(), all.begin() + k);
  sq_dists.resize(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i)
    sq_dists[static_cast<std::size_t>(i)] = static_cast<float>(d2(indices[static_cast<std::size_t>(i)]));
  return k;
}

}  // namespace pcl_ls3d
