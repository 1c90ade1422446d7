/// \file point14_context.cpp
/// \brief The POINT14 record fields, return contexts and per-channel state (see point14_context.h).

#include "point14_context.h"

#include "io/las_format.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

// LASzip's map of (number of returns n, return number r) to six contexts: single, first of two,
// last of two, first / intermediate / last of more. Invalid pairs (r > n, zeros) get contexts
// too, because real files contain them. A constant of the format, indexed [n][r].
constexpr std::uint8_t kReturnMap6[16][16] = {
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5}, {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3}, {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5},
};

}  // namespace

Point14
unpackPoint14(const std::uint8_t* record)
{
  Point14 p;
  p.x = las::get<std::int32_t>(record);
  p.y = las::get<std::int32_t>(record + 4);
  p.z = las::get<std::int32_t>(record + 8);
  p.intensity = las::get<std::uint16_t>(record + 12);
  p.return_number = record[14] & 0x0F;
  p.number_of_returns = record[14] >> 4;
  // Byte 15: classification flags (bits 0–3), channel (4–5), scan direction (6), edge (7).
  p.flags = static_cast<std::uint8_t>((record[15] & 0x0F) | ((record[15] >> 2) & 0x30));
  p.channel = (record[15] >> 4) & 0x03;
  p.classification = record[16];
  p.user_data = record[17];
  p.scan_angle = las::get<std::int16_t>(record + 18);
  p.point_source = las::get<std::uint16_t>(record + 20);
  p.gps_time = las::get<std::uint64_t>(record + 22);
  return p;
}

void
packPoint14(const Point14& p, std::uint8_t* record)
{
  las::put<std::int32_t>(record, p.x);
  las::put<std::int32_t>(record + 4, p.y);
  las::put<std::int32_t>(record + 8, p.z);
  las::put<std::uint16_t>(record + 12, p.intensity);
  record[14] = static_cast<std::uint8_t>((p.return_number & 0x0F) | (p.number_of_returns << 4));
  record[15] =
      static_cast<std::uint8_t>((p.flags & 0x0F) | ((p.channel & 0x03) << 4) | ((p.flags & 0x30) << 2));
  record[16] = p.classification;
  record[17] = p.user_data;
  las::put<std::int16_t>(record + 18, p.scan_angle);
  las::put<std::uint16_t>(record + 20, p.point_source);
  las::put<std::uint64_t>(record + 22, p.gps_time);
}

ReturnContext
returnContext(unsigned n, unsigned r)
{
  n &= 0x0F;
  r &= 0x0F;
  const unsigned spread = n > r ? n - r : r - n;
  return {kReturnMap6[n][r], spread < 7 ? spread : 7, (r == 1 ? 2u : 0u) + (r >= n ? 1u : 0u)};
}

unsigned
previousReturnContext(const Point14& last)
{
  return (last.return_number == 1 ? 1u : 0u) + (last.return_number >= last.number_of_returns ? 2u : 0u) +
         (last.gps_time_changed ? 4u : 0u);
}

Point14Context::Point14Context()
    : changed_values{SymbolModel(128), SymbolModel(128), SymbolModel(128), SymbolModel(128),
                     SymbolModel(128), SymbolModel(128), SymbolModel(128), SymbolModel(128)},
      scanner_channel(3), return_number_gps_same(13), dx(32, 2), dy(32, 22), z(32, 20), intensity(16, 4),
      scan_angle(16, 2), point_source(16, 1)
{}

void
Point14Context::start(const Point14& from)
{
  for (SymbolModel& m : changed_values)
    m.reset();
  scanner_channel.reset();
  return_number_gps_same.reset();
  for (auto* models : {&number_of_returns, &return_number})
    for (auto& m : *models)
      if (m)
        m->reset();
  for (auto* models : {&classification, &flags, &user_data})
    for (auto& m : *models)
      if (m)
        m->reset();
  for (IntegerCompressor* ic : {&dx, &dy, &z, &intensity, &scan_angle, &point_source})
    ic->reset();
  x_median = {};
  y_median = {};
  last_z.fill(from.z);
  last_intensity.fill(from.intensity);
  gps.start(from.gps_time);
  last = from;
  last.gps_time_changed = false;
  in_use = true;
}

SymbolModel&
lazyModel(std::unique_ptr<SymbolModel>& slot, std::uint32_t symbols)
{
  if (!slot)
    slot = std::make_unique<SymbolModel>(symbols);
  return *slot;
}

Point14Context&
contextOf(std::array<std::unique_ptr<Point14Context>, 4>& contexts, unsigned channel)
{
  std::unique_ptr<Point14Context>& slot = contexts[channel & 3];
  if (!slot)
    slot = std::make_unique<Point14Context>();
  return *slot;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
