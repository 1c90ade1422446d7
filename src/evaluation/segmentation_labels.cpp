#include <pcl_ls3d/evaluation/segmentation_labels.h>

#include <cmath>
#include <map>

namespace pcl_ls3d {
namespace evaluation {

std::vector<std::uint32_t>
labelsFromSegments(const std::vector<pcl::PointIndices>& segments, std::size_t num_points)
{
  std::vector<std::uint32_t> labels(num_points, 0);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (int idx : segments[s].indices)
      if (idx >= 0 && static_cast<std::size_t>(idx) < num_points && labels[idx] == 0)
        labels[static_cast<std::size_t>(idx)] = static_cast<std::uint32_t>(s + 1);
  return labels;
}

std::vector<int>
classCodesFromSegments(const std::vector<pcl::PointIndices>& segments,
                       const std::vector<segmentation::ObjectClass>& classes, std::size_t num_points)
{
  std::vector<int> codes(num_points, 0);
  if (classes.size() != segments.size())
    return codes;
  const std::vector<std::uint32_t> labels = labelsFromSegments(segments, num_points);
  for (std::size_t i = 0; i < num_points; ++i)
    if (labels[i] > 0)
      codes[i] = segmentation::lasCode(classes[labels[i] - 1]);
  return codes;
}

std::vector<pcl::PointIndices>
segmentsFromLabels(const std::vector<std::uint32_t>& labels)
{
  std::map<std::uint32_t, std::size_t> slot;
  for (std::uint32_t l : labels)
    if (l != 0)
      slot.emplace(l, 0);
  std::size_t k = 0;
  for (auto& kv : slot)
    kv.second = k++;
  std::vector<pcl::PointIndices> segments(slot.size());
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] != 0)
      segments[slot[labels[i]]].indices.push_back(static_cast<int>(i));
  return segments;
}

std::uint32_t
segmentColour(std::uint32_t label)
{
  if (label == 0)
    return 0x808080u;
  // Golden-ratio hue walk at full saturation: neighbouring ids get distant hues.
  const double h = std::fmod(static_cast<double>(label) * 0.618033988749895, 1.0) * 6.0;
  const double v = (label % 3 == 0) ? 0.75 : 1.0;  // vary brightness too
  const int i = static_cast<int>(h);
  const double f = h - i;
  double r = 0, g = 0, b = 0;
  switch (i % 6) {
  case 0:
    r = 1;
    g = f;
    break;
  case 1:
    r = 1 - f;
    g = 1;
    break;
  case 2:
    g = 1;
    b = f;
    break;
  case 3:
    g = 1 - f;
    b = 1;
    break;
  case 4:
    r = f;
    b = 1;
    break;
  default:
    r = 1;
    b = 1 - f;
    break;
  }
  auto byte = [v](double c) { return static_cast<std::uint32_t>(c * v * 255.0 + 0.5); };
  return (byte(r) << 16) | (byte(g) << 8) | byte(b);
}

}  // namespace evaluation
}  // namespace pcl_ls3d
