#pragma once
/// \file coordinate_reference.h
/// \brief The coordinate reference system (CRS) of a map as OGC WKT, taken from what LAS files
///        declare: the WKT VLR (LASF_Projection 2112, LAS 1.4) or the GeoTIFF keys (LASF_Projection
///        34735–34737, LAS 1.0–1.3), interpreted by GDAL/PROJ so user-defined projections and
///        vertical datums come through as the file states them.

#include <pcl_ls3d/io/cloud_io.h>

#include <string>
#include <utility>
#include <vector>

namespace pcl_ls3d {
namespace maps {

/// WKT of the CRS in a LAS file's VLRs (the WKT VLR first, then the GeoTIFF keys); empty when
/// the file declares none or it cannot be interpreted (`why` then says which).
std::string
crsFromLasVlrs(const std::vector<io::LasVlr>& vlrs, std::string* why = nullptr);

/// The LAS VLR that declares \a wkt (LASF_Projection 2112, "OGC WKT", NUL-terminated): what a
/// LAS 1.4 file carries (global-encoding bit 4, set by the writer); LAS 1.0–1.3 readers that
/// know only GeoTIFF keys ignore it.
io::LasVlr
wktVlr(const std::string& wkt);

/// Makes a written cloud declare \a wkt (nothing for an empty WKT): a PCD or PLY records it in
/// its header (SaveOptions::crs_wkt), a LAS gets its WKT VLR (LAS 1.4) unless its VLRs declare a
/// CRS already (copied from a LAS input).
void
recordCrs(const std::string& wkt, io::SaveOptions& options);

/// WKT of a CRS given by a user: "EPSG:2154", a PROJ string or WKT; empty with `why` if invalid.
std::string
crsFromUserInput(const std::string& text, std::string* why = nullptr);

/// A short name of a CRS ("RGF93 v1 / Lambert-93 + NGF-IGN69 height"); empty for an empty WKT.
std::string
crsName(const std::string& wkt);

/// Metres per horizontal unit of a projected or engineering (local) CRS (1 for metres, 0.3048
/// for international feet); 0 when unknown (empty WKT, geographic or geocentric CRS).
double
crsLinearUnit(const std::string& wkt);

/// The CRS a loaded file declares: a LAS file's GeoTIFF keys or WKT VLR, else the CRS a
/// SEGMENTS.pcd (or another file of the project) records; empty when none.
std::string
crsOfFile(const io::CloudInfo& info);

/// One error line when \a path's coordinates are no lengths: "'PATH' is in degrees (WGS 84):
/// distances and heights need lengths; reproject it to a projected CRS first" (likewise for a
/// geocentric CRS); empty for a projected, engineering or no CRS.
std::string
notInLengths(const std::string& path, const std::string& wkt);

/// True when \a wkt is a geographic CRS (coordinates in degrees of latitude and longitude).
bool
crsIsGeographic(const std::string& wkt);

/// True when \a wkt is a geocentric CRS (earth-centred x, y, z: z is no height).
bool
crsIsGeocentric(const std::string& wkt);

/// Metres per unit of height: the unit of the CRS's vertical part where it has one (a compound
/// CRS: "NAD83 / Oregon LCC (m) + NAVD88 height (ftUS)" gives 0.3048006), else the horizontal
/// unit (a LAS file declaring a projected CRS alone stores z in its unit); 0 when unknown
/// (as crsLinearUnit(), and a compound CRS whose vertical unit GDAL does not show).
double
crsVerticalUnit(const std::string& wkt);

/// The label of a projected CRS's horizontal unit on maps: "m", "ft" (international or US survey
/// foot) or "units" (another length); empty when unknown (empty WKT, geographic CRS).
std::string
crsLinearUnitName(const std::string& wkt);

/// The label of \a wkt's height unit (crsVerticalUnit()), as crsLinearUnitName().
std::string
crsVerticalUnitName(const std::string& wkt);

/// True when \a wkt's heights and plan coordinates have different known units (a compound CRS
/// such as "NAD83 / Oregon LCC (m) + NAVD88 height (ftUS)").
bool
crsMixesUnits(const std::string& wkt);

/// Plan units per height unit: the factor that brings \a wkt's heights into its plan unit
/// (0.3048006 for heights in US survey feet under a plan in metres); 1 when both units agree or
/// either is unknown.
double
planUnitsPerHeightUnit(const std::string& wkt);

/// True when both WKT describe the same CRS (OGRSpatialReference::IsSame).
bool
sameCrs(const std::string& a, const std::string& b);

/// True when the horizontal parts of both WKT are the same CRS (a compound CRS's vertical part
/// set aside: "Lambert-93 + NGF-IGN69 height" and "Lambert-93" agree in plan).
bool
sameHorizontalCrs(const std::string& a, const std::string& b);

/// Notes on the CRSs of files used together, (path, WKT) in order: for each file whose
/// horizontal CRS differs from the first declared one, "'B' declares WGS 84 / UTM 31N, 'A'
/// RGF93 v1 / Lambert-93: their coordinates are used as they are; reproject one into the other's
/// CRS unless both describe the same frame". Notes, not refusals: two definitions of one frame
/// can differ in GDAL's eyes. Files that declare no CRS, or one GDAL cannot read, give none.
/// (Heights in another unit than the plan are converted by the tools: heightConversionNote().)
std::vector<std::string>
crsNotes(const std::vector<std::pair<std::string, std::string>>& files);

/// The line that says \a path's heights are converted to the plan unit for \a purpose ("the
/// matching", "the adjustment"): "'PATH' declares heights in ft and plan coordinates in m
/// (NAME): heights are converted to m (x 0.3048006) for PURPOSE; transformations and written
/// clouds are in the file's units"; for a file that declares no CRS and is taken in \a wkt's
/// units (\a declared false) "'PATH' declares no CRS, taken as heights in ft and plan ...".
/// Empty when \a wkt needs no conversion (planUnitsPerHeightUnit() is 1).
std::string
heightConversionNote(const std::string& path, const std::string& wkt, bool declared,
                     const std::string& purpose);

}  // namespace maps
}  // namespace pcl_ls3d
