#pragma once
/// \file strip_io.h
/// \brief Strips in and out of files. In: every input file is one strip, or (split by the LAS
///        point-source id) every flight-line id over all inputs is one strip; LAS records are
///        read raw so the withheld and synthetic flags are seen. Out: each input written again
///        with its points corrected, in input order — LAS by a record-level rewrite (every
///        attribute and VLR byte-identical, only X, Y, Z and the header bounds change), PCD,
///        PLY and ASCII XYZ through the project's writers.

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/strips/strip.h>

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Which points of which files form a strip.
struct StripSource
{
  std::string name;
  int point_source_id = -1;                               ///< −1: all points of the files
  std::vector<int> files;                                 ///< indices into the input list
  Eigen::Vector3d file_origin = Eigen::Vector3d::Zero();  ///< O + o_k, file coordinates
};

/// \brief One input file.
struct InputFile
{
  std::string path;
  std::string format;   ///< "las", "pcd", "ply", "xyz"
  std::string crs_wkt;  ///< declared (LAS VLRs, PCD header; empty when none)
  std::size_t points = 0;
  std::map<int, std::size_t> point_sources;  ///< point-source id → points (LAS)
};

/// \brief The CRS whose units input \a f is taken in: its own, or for an input that declares
///        none (a PCD or XYZ strip exported from the others) the first declared one.
const std::string&
heightCrs(const std::vector<InputFile>& inputs, std::size_t f);

/// \brief Plan units per height unit of input \a f (of heightCrs()): the block is adjusted with
///        heights in the plan unit and corrected files are written in their own.
double
heightFactor(const std::vector<InputFile>& inputs, std::size_t f);

/// \brief How strips are formed and which points are observed.
struct StripLoadOptions
{
  bool split_by_point_source = false;
  bool exclude_withheld = true;
  bool exclude_synthetic = true;
};

/// \brief The loaded block.
struct LoadedStrips
{
  std::vector<InputFile> inputs;
  std::vector<StripSource> sources;  ///< one per strip
  std::vector<Strip> strips;
  Eigen::Vector3d block_origin = Eigen::Vector3d::Zero();  ///< file = block + this
  std::size_t unassigned = 0;                              ///< points with point-source id 0 (split only)
  std::string crs_wkt;                                     ///< of the first input that declares one
  std::vector<std::string> notes;
};

/// Reads the inputs and forms the strips. False with a one-line reason (unreadable or
/// compressed file, a split that finds fewer than two flight lines, ...).
bool
loadStrips(const std::vector<std::string>& paths, const StripLoadOptions& options, LoadedStrips& out,
           std::string& error);

/// Reads one strip again for a distributed job, with the origins the plan chose (so its local
/// coordinates equal those of the planning run bit for bit).
bool
loadStrip(const std::vector<InputFile>& inputs, const StripSource& source,
          const Eigen::Vector3d& block_origin, const StripLoadOptions& options, Strip& strip,
          std::string& error);

/// \brief One output file: an input (all its points, or one point-source id of it).
struct OutputUnit
{
  int file = -1;
  int point_source_id = -1;  ///< −1: every point of the file
  std::string path;          ///< where it goes
};

/// The outputs for `dir`: each input under its own name, or with a split one file per input and
/// point-source id, NAME_psid<ID>.EXT (ids without a strip, e.g. 0, are written unchanged);
/// `keep_files` writes each split input whole under its own name instead. The format is the
/// input's (LAS, LAZ, PCD, ...); a COPC input "NAME.copc.laz" gives "NAME.laz" (plain LAZ: its
/// moved records no longer fit the octree).
std::vector<OutputUnit>
outputUnits(const LoadedStrips& block, const std::string& dir, bool keep_files);

/// Writes one output with every point moved by its strip's correction (4 × 4, file
/// coordinates; strips identified by point-source id when split, else the file's strip).
/// Refuses to replace an existing file or an input. False with a one-line reason.
bool
writeCorrected(const LoadedStrips& block, const OutputUnit& unit,
               const std::vector<Eigen::Matrix4d>& corrections, std::string& error);

/// Strips from one cloud in memory (file coordinates = local + cloud_origin), split by
/// point-source id or as one strip; block origin = cloud_origin. For generated blocks and tests.
std::vector<Strip>
stripsFromCloud(const pcl::PointCloud<PointLiDAR>& cloud, bool split_by_point_source);

}  // namespace strips
}  // namespace pcl_ls3d
