#pragma once
/// \file truth_json.h
/// \brief Truth files of the generators as JSON text (nlohmann_json stays private to the library).
///
/// Common keys: "generator", "seed", "settings", "origin" (global = local + origin),
/// "convention" (x' = t + m R_Y(φ) R_X(ω) R_Z(κ) x). Every transform is given as
///   "transformation": 4×4 row-major matrix (array of 4 rows) in WRITTEN (global) coordinates,
///   "transformation_local": the same in local coordinates,
///   "parameters": {tx, ty, tz, phi, omega, kappa, m} in local coordinates, i.e. rotating about
///   "parameters_frame_origin" (global coordinates of the local origin),
///   "parameters_global": the parameters of "transformation" (rotation about global 0).
/// Doubles are written in their shortest round-trip form (lossless).

#include <pcl_ls3d/synth/li_surface.h>
#include <pcl_ls3d/synth/registration_pair.h>
#include <pcl_ls3d/synth/scene.h>
#include <pcl_ls3d/synth/strip_block.h>

#include <string>

namespace pcl_ls3d {
namespace synth {

/// Pair: the source → target truth, footprints (global), counts per class, building count.
std::string
truthJson(const RegistrationPair& pair, const RegistrationPairSettings& settings);

/// Strips: per strip id, fixed flag, observed → true transform, centre, t_centre, footprint,
/// index range, times; counts.
std::string
truthJson(const StripBlock& block, const StripSettings& settings);

/// Li surface: mate → reference transform (rigid), deformation mask (indices and per node),
/// achieved percentage, position, σ, c, mean deformation.
std::string
truthJson(const LiSurface& li, const LiSurfaceSettings& settings);

/// Scene: class counts, objects (type, class, position, size, heading, points).
std::string
truthJson(const LabelledScene& scene, const SceneSettings& settings);

/// Writes text to a file; refuses an existing file unless overwrite. False + reason on failure.
bool
writeTextFile(const std::string& path, const std::string& text, bool overwrite, std::string& error);

}  // namespace synth
}  // namespace pcl_ls3d
