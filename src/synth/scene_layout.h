#pragma once
// Private: where makeScene() puts its objects (placement only; sampling is in scene.cpp).

#include <pcl_ls3d/synth/random.h>
#include <pcl_ls3d/synth/scene.h>

#include <vector>

namespace pcl_ls3d {
namespace synth {
namespace detail {

/// Ellipsoidal crown: centre (c, (base + top)/2), radii (r, r, (top − base)/2).
struct Crown
{
  Eigen::Vector2d c;
  double ground, base, top, r;
  int object;
};

/// A straight member (tower leg, brace, arm) or a catenary wire between a and b.
struct Segment
{
  Eigen::Vector3d a, b;
  double catenary_a = 0.0;  ///< 0: straight; else catenary parameter a [m] (sag below the chord)
  int object;
};

struct SceneLayout
{
  std::vector<SceneObject> objects;
  std::vector<Building> buildings;
  std::vector<int> building_object;
  std::vector<int> first_plane;  ///< per building: its plane 0 in LabelledScene::planes
  std::vector<RoofPlane> planes;
  int ground_object = -1;
  std::vector<Crown> crowns;
  std::vector<Building> cars;  ///< oriented boxes, eave_z = car top
  std::vector<int> car_object;
  std::vector<Segment> members;  ///< tower members (class 15) and wires (class 14)
};

SceneLayout
layoutScene(const SceneSettings& s, const Terrain& terrain);

/// Point of a segment at parameter u in [0, 1] (catenary sag applied for wires).
Eigen::Vector3d
segmentPoint(const Segment& seg, double u);

}  // namespace detail
}  // namespace synth
}  // namespace pcl_ls3d
