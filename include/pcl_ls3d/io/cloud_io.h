#pragma once
/// \file cloud_io.h
/// \brief One entry point to read and write point clouds (PCD, PLY, LAS 1.0–1.4, ASCII XYZ) in
///        local coordinates, with the georeferenced origin kept in double.
///
/// Coordinates. PCL points are float; a UTM northing (5e6 m) in float is quantised to 0.5 m. Every
/// reader therefore computes file coordinates in double and stores x_local = x_file - origin in
/// float; every writer restores x_file = x_local + origin in double.
///
/// Auto-origin rule (LoadOptions::use_origin == false), per axis k, over the finite points:
///   origin_k = 0                                   if max(|min_k|, |max_k|) < 1e4
///   origin_k = round((min_k + max_k) / 2)          otherwise (bounding-box centre, whole unit)
/// Below 1e4 a float's step is <= 1 mm (rounding <= 0.5 mm), so small clouds (bunny, Kinect) are not
/// shifted; a UTM tile is centred. Registering two clouds: load the first, then load the second with
/// LoadOptions{use_origin = true, origin = info_first.origin} so both share one frame.
/// A PCD that records its origin in its header (pcl_ls3d_segment's SEGMENTS.pcd, see pcd_io.h)
/// holds local floats already: that origin is used instead of the rule, and its values come back
/// unchanged as the local coordinates.
///
/// Non-finite points. Points with a NaN/inf x, y or z are dropped by every reader and counted in
/// CloudInfo::points_dropped_nonfinite; the result is always dense and unorganized (height 1).
/// If nothing finite is left, loadCloud() returns false with "no finite points in ..." unless
/// LoadOptions::allow_empty is set (then it returns true with points_loaded == 0).

#include <pcl_ls3d/point_types.h>

#include <pcl/point_cloud.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace io {

/// \brief One variable-length record of a LAS file (kept so a LAS→LAS conversion can carry the CRS).
struct LasVlr
{
  std::string user_id;  ///< 16-byte user id, trailing NULs removed
  std::uint16_t record_id = 0;
  std::string description;         ///< 32-byte description, trailing NULs removed
  std::vector<std::uint8_t> data;  ///< payload (record length after header bytes)
};

/// \brief How the point records of a LAZ file are compressed (LASzip); all zero for LAS.
struct LazInfo
{
  bool compressed = false;        ///< the records are LASzip-compressed (a .laz file)
  int compressor = 0;             ///< 1 pointwise, 2 pointwise-chunked, 3 layered-chunked
  std::uint32_t chunk_size = 0;   ///< points per chunk; 0xFFFFFFFF: chunks of varying size
  std::uint64_t chunk_count = 0;  ///< chunks holding the points
  /// The chunk table was read; false: it is missing or unusable and the chunks are found by
  /// decoding them in order (no parallel decoding then).
  bool chunk_table = false;
  std::string items;  ///< the item list, e.g. "POINT10 v2, GPSTIME11 v2"
};

/// \brief Nodes and points of one level of a COPC octree (level 0: the root).
struct CopcLevel
{
  int level = 0;
  std::size_t nodes = 0;  ///< nodes of this level that hold points
  std::uint64_t points = 0;
};

/// \brief The octree of a COPC file (a `.copc.laz`: LAZ whose variable-size chunks are the nodes
///        of an octree, listed in its hierarchy EVLR); `present` is false for any other file.
struct CopcHeaderInfo
{
  bool present = false;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< root cube's centre (file units)
  double halfsize = 0.0;                             ///< half the root cube's edge
  double spacing = 0.0;                              ///< point spacing at the root level
  std::size_t nodes = 0;                             ///< nodes holding points
  std::vector<CopcLevel> levels;                     ///< per level, from the root down
};

/// \brief LAS public-header summary (filled when CloudInfo::format == "las", LAZ included).
struct LasHeaderInfo
{
  std::uint8_t version_major = 1, version_minor = 2;
  std::uint8_t point_format = 0;             ///< 0–10 (compression bits masked off)
  std::uint16_t record_length = 0;           ///< bytes per point record in the file
  std::uint16_t extra_bytes_per_record = 0;  ///< record_length minus the format's minimum (skipped)
  std::uint16_t header_size = 0;             ///< 227 (1.0–1.2), 235 (1.3), 375 (1.4) or larger
  std::uint32_t offset_to_points = 0;
  std::uint32_t number_of_vlrs = 0;
  std::uint16_t global_encoding = 0;  ///< bit 0: adjusted standard GPS time; bit 4: WKT CRS
  std::uint16_t file_source_id = 0;
  std::uint64_t point_count = 0;  ///< legacy or 64-bit count, whichever the version uses
  std::uint32_t legacy_point_count = 0;
  std::uint64_t points_by_return[15] = {};  ///< legacy 5 counts, or the 15 of LAS 1.4
  std::string system_identifier, generating_software;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< header bounds (file units)
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  std::vector<LasVlr> vlrs;   ///< the VLRs between header and points
  std::vector<LasVlr> evlrs;  ///< LAS 1.4 extended VLRs after the points
  LazInfo laz;                ///< compression of the records (LAZ)
  CopcHeaderInfo copc;        ///< the COPC octree, when the file is COPC
};

/// \brief A box query: loadCloud() keeps only the points inside `box` (file coordinates, the
///        faces included). A COPC file decodes only the octree nodes whose cube meets the box
///        (in parallel); any other file is read through and filtered (LAS and LAZ chunk by
///        chunk, keeping only the records inside).
struct Region
{
  Eigen::AlignedBox3d box;  ///< file coordinates; only x and y are compared unless use_z
  bool use_z = false;
  /// COPC only: read nodes down to this octree level (0: the root only), a coarser but evenly
  /// spread subset of the points in the box. < 0: every level. Other files are refused with
  /// a level, as they have no octree to thin by.
  int max_level = -1;
};

/// \brief What a region query read (CloudInfo::region).
struct RegionInfo
{
  bool applied = false;              ///< LoadOptions::region was given
  bool copc = false;                 ///< answered from the COPC octree
  std::size_t nodes = 0;             ///< COPC: nodes holding points
  std::size_t nodes_read = 0;        ///< COPC: nodes decoded (their cube meets the box)
  std::uint64_t points_decoded = 0;  ///< records decoded (COPC: of the nodes read)
};

/// \brief How loadCloud() reads a file.
struct LoadOptions
{
  bool use_origin = false;                           ///< true: shift by `origin` instead of choosing one
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< forced origin (file units) when use_origin
  bool allow_empty = false;                          ///< true: 0 finite points is not an error
  /// ASCII XYZ column names, comma separated, e.g. "x,y,z,intensity,classification". Empty: use a
  /// header line if the file has one (see xyz_io.h), else x y z in columns 1–3, the rest ignored.
  std::string xyz_columns;
  /// Keep only the points inside this box (see Region); CloudInfo::region says what was read.
  std::optional<Region> region;
};

/// \brief How saveCloud() writes a file.
struct SaveOptions
{
  bool overwrite = false;                          ///< refuse to replace an existing file unless true
  bool binary = true;                              ///< PCD/PLY: binary (true) or ASCII
  Eigen::Vector3d las_scale{0.001, 0.001, 0.001};  ///< LAS writer quantum (file units)
  /// LAS offset. When las_use_offset is false the writer uses the rounded bbox centre.
  bool las_use_offset = false;
  Eigen::Vector3d las_offset = Eigen::Vector3d::Zero();
  std::uint8_t las_point_format = 3;   ///< 0–10 (6–10 need version 1.4)
  std::uint8_t las_minor_version = 2;  ///< 0–4 (LAS 1.x)
  /// Sets global-encoding bit 0 (LAS 1.2+): the gps_time values are adjusted standard GPS time
  /// (GPS seconds − 1e9). Default false = GPS week time. The writer never converts the values.
  bool las_adjusted_standard_gps_time = false;
  std::vector<LasVlr> las_vlrs;  ///< VLRs to write (e.g. copied from the input)
  /// ASCII XYZ: x, y, z with this many fixed decimals; -1 (default) = full precision, the
  /// shortest text that reads back as exactly the double x_local + origin.
  int xyz_decimals = -1;
  /// OGC WKT of the cloud's CRS. PCD: recorded as a "# pcl_ls3d crs" header line (pcd_io.h),
  /// PLY as a "comment pcl_ls3d crs" line (ply_io.h), which loadCloud() gives back as
  /// CloudInfo::file_crs_wkt. LAS: not used (the CRS travels in las_vlrs; maps::recordCrs()
  /// sets both). XYZ: no place for it.
  std::string crs_wkt;
};

/// \brief What a reader found.
struct CloudInfo
{
  std::string format;                                ///< "las" (LAZ too: las.laz), "pcd", "ply", "xyz"
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< local origin subtracted from every point (double)
  /// PCD: the origin its header records ("# pcl_ls3d origin", pcd_io.h; the file holds local
  /// floats, x_file = stored value + file_origin); zero for any other file.
  Eigen::Vector3d file_origin = Eigen::Vector3d::Zero();
  bool has_file_origin = false;  ///< the header records an origin (it may be zero)
  /// PCD, PLY: the OGC WKT its header records ("# pcl_ls3d crs", pcd_io.h; "comment pcl_ls3d
  /// crs", ply_io.h); empty for other files (a LAS file's CRS is in las.vlrs).
  std::string file_crs_wkt;
  /// PCD: its header marks it as pcl_ls3d_segment's SEGMENTS.pcd (kPcdSegmentsMarker, pcd_io.h):
  /// its label field holds segment ids and is not read as the classification.
  bool segments_file = false;
  std::size_t points_in_file = 0, points_loaded = 0, points_dropped_nonfinite = 0;
  /// Points left out by LoadOptions::region (outside the box, or in nodes below its level):
  /// points_loaded + points_dropped_nonfinite + points_outside_region == points_in_file.
  std::size_t points_outside_region = 0;
  RegionInfo region;                                   ///< what a region query read
  std::vector<std::size_t> nonfinite_indices;          ///< file indices of the dropped points, ascending
  Eigen::Vector3d min_file = Eigen::Vector3d::Zero();  ///< bounds of the loaded points, file units
  Eigen::Vector3d max_file = Eigen::Vector3d::Zero();
  std::vector<std::string> fields;       ///< point fields mapped into PointLiDAR
                                         ///< (a SEGMENTS.pcd's label is not)
  std::size_t xyz_unmapped_columns = 0;  ///< XYZ: columns on the first data line not mapped
  LasHeaderInfo las;                     ///< valid when format == "las"

  /// Was a field of this name read into PointLiDAR (fields)?
  bool
  hasField(const std::string& name) const
  {
    return std::find(fields.begin(), fields.end(), name) != fields.end();
  }
};

/// Loads PCD, PLY, LAS (1.0–1.4, formats 0–10), LAZ (LASzip-compressed LAS, COPC included, see
/// las_io.h) or ASCII XYZ (by extension and/or signature) into local coordinates
/// x_local = x_file - origin. With LoadOptions::region only the points inside its box are kept
/// (and the auto origin is chosen from them); a region holding none is an error unless
/// allow_empty. Returns false with a one-line reason.
bool
loadCloud(const std::string& path, pcl::PointCloud<PointLiDAR>& cloud, CloudInfo& info, std::string& error,
          const LoadOptions& options = {});

/// Writes by extension (.pcd .ply .las .laz .xyz/.txt), restoring x_file = x_local + origin in
/// double.
/// PCD/PLY store x, y, z as FLOAT64 when origin is non-zero (FLOAT32 otherwise).
bool
saveCloud(const std::string& path, const pcl::PointCloud<PointLiDAR>& cloud, const Eigen::Vector3d& origin,
          std::string& error, const SaveOptions& options = {});

/// Can saveCloud() write a file of this name's format? False with the reason (the extension).
bool
canSaveFormat(const std::string& path, std::string& why);

/// Same file (after resolving paths/links)? Tools use it to refuse overwriting an input.
bool
isSameFile(const std::string& a, const std::string& b);

/// The auto-origin rule above applied to file-coordinate bounds.
Eigen::Vector3d
chooseOrigin(const Eigen::Vector3d& min_file, const Eigen::Vector3d& max_file);

/// Lower-case extension without the dot ("las", "pcd", ...), "" when none.
std::string
fileExtension(const std::string& path);

}  // namespace io
}  // namespace pcl_ls3d
