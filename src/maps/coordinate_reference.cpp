#include <pcl_ls3d/maps/coordinate_reference.h>

#include "gdal_session.h"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

namespace pcl_ls3d {
namespace maps {

namespace {

constexpr std::uint16_t kWktRecord = 2112;
constexpr std::uint16_t kGeoKeys = 34735, kGeoDoubles = 34736, kGeoAscii = 34737;

const io::LasVlr*
findProjectionVlr(const std::vector<io::LasVlr>& vlrs, std::uint16_t record)
{
  for (const io::LasVlr& v : vlrs)
    if (v.user_id == "LASF_Projection" && v.record_id == record && !v.data.empty())
      return &v;
  return nullptr;
}

// --- a one-pixel GeoTIFF in memory, carrying the LAS GeoTIFF keys for GDAL to interpret ------

struct TiffEntry
{
  std::uint16_t tag, type;
  std::uint32_t count;
  std::vector<std::uint8_t> data;  // little-endian values
};

template <typename T>
void
append(std::vector<std::uint8_t>& out, T v)
{
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

TiffEntry
shortEntry(std::uint16_t tag, std::uint16_t v)
{
  TiffEntry e{tag, 3, 1, {}};
  append(e.data, v);
  return e;
}

TiffEntry
longEntry(std::uint16_t tag, std::uint32_t v)
{
  TiffEntry e{tag, 4, 1, {}};
  append(e.data, v);
  return e;
}

TiffEntry
doublesEntry(std::uint16_t tag, const std::vector<double>& v)
{
  TiffEntry e{tag, 12, static_cast<std::uint32_t>(v.size()), {}};
  for (double d : v)
    append(e.data, d);
  return e;
}

// Header, one IFD (entries sorted by tag), out-of-line values, then the single pixel.
std::vector<std::uint8_t>
buildTiff(std::vector<TiffEntry> entries)
{
  const std::uint32_t ifd_size = 2 + 12 * static_cast<std::uint32_t>(entries.size() + 1) + 4;
  std::uint32_t data_offset = 8 + ifd_size;
  std::vector<std::uint8_t> out = {'I', 'I', 42, 0, 8, 0, 0, 0};
  std::vector<std::uint8_t> tail;
  entries.push_back(longEntry(273, 0));  // StripOffsets, patched below
  std::sort(entries.begin(), entries.end(),
            [](const TiffEntry& a, const TiffEntry& b) { return a.tag < b.tag; });
  append(out, static_cast<std::uint16_t>(entries.size()));
  for (TiffEntry& e : entries) {
    append(out, e.tag);
    append(out, e.type);
    append(out, e.count);
    if (e.tag == 273) {
      e.data.clear();
      append(e.data, std::uint32_t(0));  // placeholder: pixel offset known after the data
    }
    if (e.data.size() <= 4) {
      e.data.resize(4, 0);
      out.insert(out.end(), e.data.begin(), e.data.end());
    } else {
      append(out, static_cast<std::uint32_t>(data_offset + tail.size()));
      tail.insert(tail.end(), e.data.begin(), e.data.end());
      if (tail.size() % 2)
        tail.push_back(0);  // word alignment
    }
  }
  append(out, std::uint32_t(0));  // no next IFD
  out.insert(out.end(), tail.begin(), tail.end());
  const std::uint32_t pixel = static_cast<std::uint32_t>(out.size());
  out.push_back(0);
  // Patch StripOffsets (its value sits inline in its IFD entry).
  for (std::size_t k = 0; k < entries.size(); ++k)
    if (entries[k].tag == 273)
      std::memcpy(out.data() + 8 + 2 + 12 * k + 8, &pixel, 4);
  return out;
}

std::string
wktOfGeoKeys(const std::vector<io::LasVlr>& vlrs, std::string* why)
{
  const io::LasVlr* keys = findProjectionVlr(vlrs, kGeoKeys);
  if (!keys)
    return "";
  std::vector<TiffEntry> entries = {shortEntry(256, 1),
                                    shortEntry(257, 1),
                                    shortEntry(258, 8),
                                    shortEntry(259, 1),
                                    shortEntry(262, 1),
                                    shortEntry(277, 1),
                                    shortEntry(278, 1),
                                    longEntry(279, 1),
                                    doublesEntry(33550, {1.0, 1.0, 0.0}),
                                    doublesEntry(33922, {0, 0, 0, 0, 0, 0})};
  entries.push_back(
      {kGeoKeys, 3, static_cast<std::uint32_t>(keys->data.size() / 2),
       std::vector<std::uint8_t>(keys->data.begin(), keys->data.end() - keys->data.size() % 2)});
  if (const io::LasVlr* d = findProjectionVlr(vlrs, kGeoDoubles))
    entries.push_back({kGeoDoubles, 12, static_cast<std::uint32_t>(d->data.size() / 8),
                       std::vector<std::uint8_t>(d->data.begin(), d->data.end() - d->data.size() % 8)});
  if (const io::LasVlr* a = findProjectionVlr(vlrs, kGeoAscii)) {
    std::vector<std::uint8_t> text(a->data.begin(), a->data.end());
    if (text.back() != 0)
      text.push_back(0);
    entries.push_back({kGeoAscii, 2, static_cast<std::uint32_t>(text.size()), text});
  }
  std::vector<std::uint8_t> tiff = buildTiff(std::move(entries));

  detail::QuietGdal quiet;
  static std::atomic<int> counter{0};
  const std::string name = "/vsimem/pcl_ls3d_geokeys_" + std::to_string(counter++) + ".tif";
  VSIFCloseL(VSIFileFromMemBuffer(name.c_str(), tiff.data(), tiff.size(), FALSE));
  // Vertical keys become a compound CRS only on request.
  CPLSetThreadLocalConfigOption("GTIFF_REPORT_COMPD_CS", "YES");
  GDALDatasetH ds = GDALOpen(name.c_str(), GA_ReadOnly);
  std::string wkt;
  if (ds) {
    const char* ref = GDALGetProjectionRef(ds);
    wkt = ref ? ref : "";
    GDALClose(ds);
  }
  CPLSetThreadLocalConfigOption("GTIFF_REPORT_COMPD_CS", nullptr);
  VSIUnlink(name.c_str());
  if (wkt.empty() && why)
    *why = "the GeoTIFF keys of the LAS file describe no CRS GDAL knows";
  return wkt;
}

std::unique_ptr<OGRSpatialReference>
parse(const std::string& wkt)
{
  if (wkt.empty())
    return nullptr;
  detail::QuietGdal quiet;
  auto srs = std::make_unique<OGRSpatialReference>();
  if (srs->importFromWkt(wkt.c_str()) != OGRERR_NONE)
    return nullptr;
  return srs;
}

std::string
exportWkt(const OGRSpatialReference& srs)
{
  char* out = nullptr;
  const char* options[] = {"FORMAT=WKT2_2018", nullptr};
  std::string wkt;
  if (srs.exportToWkt(&out, options) == OGRERR_NONE && out)
    wkt = out;
  CPLFree(out);
  return wkt;
}

}  // namespace

std::string
crsFromLasVlrs(const std::vector<io::LasVlr>& vlrs, std::string* why)
{
  if (const io::LasVlr* w = findProjectionVlr(vlrs, kWktRecord)) {
    const std::string text(w->data.begin(), w->data.end());
    const std::string wkt = text.substr(0, text.find('\0'));
    if (auto srs = parse(wkt))
      return exportWkt(*srs);
    if (why)
      *why = "the WKT VLR of the LAS file cannot be parsed";
  }
  return wktOfGeoKeys(vlrs, why);
}

std::string
crsFromUserInput(const std::string& text, std::string* why)
{
  detail::QuietGdal quiet;
  OGRSpatialReference srs;
  if (text.empty() || srs.SetFromUserInput(text.c_str()) != OGRERR_NONE) {
    if (why)
      *why = "'" + text + "' is not a coordinate reference system GDAL knows";
    return "";
  }
  return exportWkt(srs);
}

std::string
crsName(const std::string& wkt)
{
  const auto srs = parse(wkt);
  if (!srs)
    return "";
  const char* name = srs->GetName();
  return name ? name : "";
}

double
crsLinearUnit(const std::string& wkt)
{
  const auto srs = parse(wkt);
  if (!srs || !(srs->IsProjected() || srs->IsLocal()))
    return 0.0;
  return srs->GetLinearUnits(nullptr);  // of the horizontal part of a compound CRS
}

bool
crsIsGeographic(const std::string& wkt)
{
  const auto srs = parse(wkt);
  return srs && srs->IsGeographic();
}

bool
crsIsGeocentric(const std::string& wkt)
{
  const auto srs = parse(wkt);
  return srs && srs->IsGeocentric();
}

std::string
crsOfFile(const io::CloudInfo& info)
{
  return info.format == "las" ? crsFromLasVlrs(info.las.vlrs) : info.file_crs_wkt;
}

std::string
notInLengths(const std::string& path, const std::string& wkt)
{
  const bool degrees = crsIsGeographic(wkt);
  if (!degrees && !crsIsGeocentric(wkt))
    return "";
  return "'" + path + "' is in " + (degrees ? "degrees" : "earth-centred coordinates") + " (" + crsName(wkt) +
         "): distances and heights need lengths; reproject it to a projected "
         "CRS first";
}

double
crsVerticalUnit(const std::string& wkt)
{
  const auto srs = parse(wkt);
  if (!srs || !(srs->IsProjected() || srs->IsLocal()))
    return 0.0;
  if (!srs->IsCompound())
    return srs->GetLinearUnits(nullptr);
  // The vertical part's own unit; not guessed when GDAL's tree does not show it.
  return srs->GetAttrNode("VERT_CS") != nullptr ? srs->GetTargetLinearUnits("VERT_CS", nullptr) : 0.0;
}

namespace {

/// "m", "ft" (international or US survey foot) or "units"; empty for no unit.
std::string
unitName(double metres)
{
  if (!(metres > 0.0))
    return "";
  if (std::abs(metres - 1.0) <= 1e-9)
    return "m";
  return std::abs(metres - 0.3048) < 1e-6 ? "ft" : "units";  // 1e-6 takes the US foot too
}

}  // namespace

std::string
crsLinearUnitName(const std::string& wkt)
{
  return unitName(crsLinearUnit(wkt));
}

std::string
crsVerticalUnitName(const std::string& wkt)
{
  return unitName(crsVerticalUnit(wkt));
}

bool
crsMixesUnits(const std::string& wkt)
{
  const double plan = crsLinearUnit(wkt), height = crsVerticalUnit(wkt);
  return plan > 0.0 && height > 0.0 && std::abs(plan / height - 1.0) >= 1e-6;
}

double
planUnitsPerHeightUnit(const std::string& wkt)
{
  return crsMixesUnits(wkt) ? crsVerticalUnit(wkt) / crsLinearUnit(wkt) : 1.0;
}

bool
sameCrs(const std::string& a, const std::string& b)
{
  const auto sa = parse(a), sb = parse(b);
  return sa && sb && sa->IsSame(sb.get());
}

bool
sameHorizontalCrs(const std::string& a, const std::string& b)
{
  if (a == b)
    return true;
  const auto sa = parse(a), sb = parse(b);
  if (!sa || !sb)
    return false;
  detail::QuietGdal quiet;
  sa->StripVertical();  // no-op on a CRS without a vertical part
  sb->StripVertical();
  return sa->IsSame(sb.get());
}

std::vector<std::string>
crsNotes(const std::vector<std::pair<std::string, std::string>>& files)
{
  std::vector<std::string> notes;
  const std::pair<std::string, std::string>* first = nullptr;  // the first declared CRS
  for (const auto& file : files) {
    const auto& [path, wkt] = file;
    if (!parse(wkt))  // none, or unreadable: no evidence of anything
      continue;
    if (!first)
      first = &file;
    else if (!sameHorizontalCrs(first->second, wkt))
      notes.push_back("'" + path + "' declares " + crsName(wkt) + ", '" + first->first + "' " +
                      crsName(first->second) +
                      ": their coordinates are used as they are; "
                      "reproject one into the other's CRS unless both describe the same frame");
  }
  return notes;
}

std::string
heightConversionNote(const std::string& path, const std::string& wkt, bool declared,
                     const std::string& purpose)
{
  const double factor = planUnitsPerHeightUnit(wkt);
  if (factor == 1.0)
    return "";
  char times[32];
  std::snprintf(times, sizeof times, "%.7g", factor);
  const std::string plan = crsLinearUnitName(wkt);
  return "'" + path + "' " + (declared ? "declares" : "declares no CRS, taken as") + " heights in " +
         crsVerticalUnitName(wkt) + " and plan coordinates in " + plan + " (" + crsName(wkt) +
         "): heights are converted to " + plan + " (x " + times + ") for " + purpose +
         "; transformations and written clouds are in the file's units";
}

io::LasVlr
wktVlr(const std::string& wkt)
{
  io::LasVlr v;
  v.user_id = "LASF_Projection";
  v.record_id = kWktRecord;
  v.description = "OGC WKT";
  v.data.assign(wkt.begin(), wkt.end());
  v.data.push_back(0);
  return v;
}

void
recordCrs(const std::string& wkt, io::SaveOptions& options)
{
  if (wkt.empty())
    return;
  options.crs_wkt = wkt;
  if (crsFromLasVlrs(options.las_vlrs).empty()) {
    options.las_vlrs.push_back(wktVlr(wkt));
    options.las_minor_version = 4;
  }
}

}  // namespace maps
}  // namespace pcl_ls3d
