#pragma once
/// \file point14_context.h
/// \brief Private: what the POINT14 coder keeps per scanner channel (the last record, the
///        predictions and every adaptive model), the record's fields unpacked, and LASzip's
///        return-number context tables. Shared by the POINT14 decoder and encoder.

#include "arithmetic_models.h"
#include "gps_time14.h"
#include "integer_compressor.h"
#include "streaming_median.h"

#include <array>
#include <cstdint>
#include <memory>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// Bytes of a LAS 1.4 point record of formats 6–10 up to the GPS time (the POINT14 item).
constexpr std::size_t kPoint14Bytes = 30;

/// \brief The fields of a POINT14 record as the coder sees them.
struct Point14
{
  std::int32_t x = 0, y = 0, z = 0;
  std::uint16_t intensity = 0;
  std::uint8_t return_number = 0, number_of_returns = 0;  ///< 4 bits each
  std::uint8_t flags = 0;    ///< edge << 5 | scan direction << 4 | classification flags (6 bits)
  std::uint8_t channel = 0;  ///< scanner channel (2 bits)
  std::uint8_t classification = 0, user_data = 0;
  std::int16_t scan_angle = 0;
  std::uint16_t point_source = 0;
  std::uint64_t gps_time = 0;     ///< the double's bit pattern
  bool gps_time_changed = false;  ///< coder state: did this record's time differ from its last
};

Point14
unpackPoint14(const std::uint8_t* record);
void
packPoint14(const Point14& p, std::uint8_t* record);

/// Where the record sits in its pulse, from its return number r and number of returns n: the
/// contexts LASzip derives from them.
struct ReturnContext
{
  unsigned map;    ///< 0–5, LASzip's 6-context (n, r) map: selects the X / Y medians
  unsigned level;  ///< 0–7, min(|n − r|, 7): selects the Z prediction
  unsigned cpr;    ///< first (2) + last (1) return: intensity and classification contexts
};

ReturnContext
returnContext(unsigned n, unsigned r);

/// Context of the changed-fields symbol: first (1) + last (2) return of the previous record,
/// + 4 when its GPS time had changed.
unsigned
previousReturnContext(const Point14& last);

/// \brief One scanner channel's state. Models indexed by a previous value are created on first
///        use, as LASzip does (most are never needed); all are reset when the context starts.
struct Point14Context
{
  Point14Context();

  /// Starts the context for a chunk, or on the first switch to this channel within one, with
  /// `from` as the last record (LASzip seeds a new channel from the previous channel's record).
  void
  start(const Point14& from);

  bool in_use = false;
  Point14 last;

  // Layer "channel, returns, XY".
  std::array<SymbolModel, 8> changed_values;
  SymbolModel scanner_channel, return_number_gps_same;
  std::array<std::unique_ptr<SymbolModel>, 16> number_of_returns, return_number;
  IntegerCompressor dx, dy;
  std::array<StreamingMedian5, 12> x_median, y_median;
  // Layer Z.
  IntegerCompressor z;
  std::array<std::int32_t, 8> last_z{};
  // Layers classification, flags, user data (models by the previous value).
  std::array<std::unique_ptr<SymbolModel>, 64> classification, flags, user_data;
  // Layers intensity, scan angle, point source, GPS time.
  IntegerCompressor intensity, scan_angle, point_source;
  std::array<std::uint16_t, 8> last_intensity{};
  GpsTime14 gps;
};

/// The model in `slot`, created (with `symbols` symbols) on first use.
SymbolModel&
lazyModel(std::unique_ptr<SymbolModel>& slot, std::uint32_t symbols);

/// The context of `channel` in `contexts`, allocated on first use.
Point14Context&
contextOf(std::array<std::unique_ptr<Point14Context>, 4>& contexts, unsigned channel);

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
