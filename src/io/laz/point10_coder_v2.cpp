/// \file point10_coder_v2.cpp
/// \brief POINT10 version 2: the 20 bytes every point format 0–5 record starts with (X, Y, Z,
///        intensity, return bits, classification, scan angle, user data, point source).
///
/// A symbol of six bits says which of the non-coordinate fields changed; each changed field is
/// coded against its previous value. X and Y are coded as the difference from the previous record
/// against the streaming median of the last differences, Z against the last Z of the same return
/// level; the coordinate models are split by the record's return context so that first and last
/// returns of multi-return pulses do not spoil each other's statistics.

#include "integer_compressor.h"
#include "pointwise_items.h"

#include "io/las_format.h"

#include <algorithm>
#include <cstring>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

// Byte offsets in the POINT10 item.
constexpr std::size_t kX = 0, kY = 4, kZ = 8, kIntensity = 12, kReturns = 14, kClass = 15, kScanAngle = 16,
                      kUserData = 17, kSource = 18;

// Bits of the "changed" symbol.
constexpr std::uint32_t kReturnsChanged = 32, kIntensityChanged = 16, kClassChanged = 8, kAngleChanged = 4,
                        kUserChanged = 2, kSourceChanged = 1;

std::uint32_t
returnNumber(const std::uint8_t* p)
{
  return p[kReturns] & 7u;
}

std::uint32_t
numberOfReturns(const std::uint8_t* p)
{
  return (p[kReturns] >> 3) & 7u;
}

std::uint32_t
scanDirection(const std::uint8_t* p)
{
  return (p[kReturns] >> 6) & 1u;
}

/// Context of Y from the bits X needed, and of Z from the bits X and Y needed.
std::uint32_t
yContext(std::uint32_t n, std::uint32_t k_x)
{
  return (n == 1) + (k_x < 20 ? (k_x & ~1u) : 20u);
}

std::uint32_t
zContext(std::uint32_t n, std::uint32_t k_xy)
{
  return (n == 1) + (k_xy < 18 ? (k_xy & ~1u) : 18u);
}

class Point10CoderV2 final : public PointwiseItemCoder
{
public:
  void
  init(const std::uint8_t* first) override;
  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override;
  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override;

private:
  void
  decodeChangedFields(ArithmeticDecoder& dec, std::uint32_t changed);
  void
  decodeCoordinates(ArithmeticDecoder& dec, std::uint32_t n, std::uint32_t m, std::uint32_t l);

  std::uint8_t last_[20] = {};
  std::uint16_t last_intensity_[16] = {};
  std::int32_t last_height_[8] = {};
  StreamingMedian5 median_dx_[16], median_dy_[16];

  SymbolModel changed_{64};
  ByteModelsByContext returns_, class_, user_data_;
  SymbolModel scan_angle_[2] = {SymbolModel(256), SymbolModel(256)};
  IntegerCompressor intensity_{16, 4}, source_{16}, dx_{32, 2}, dy_{32, 22}, z_{32, 20};
};

void
Point10CoderV2::init(const std::uint8_t* first)
{
  for (int i = 0; i < 16; ++i) {
    median_dx_[i].reset();
    median_dy_[i].reset();
    last_intensity_[i] = 0;
  }
  std::fill(std::begin(last_height_), std::end(last_height_), 0);
  changed_.reset();
  returns_.reset();
  class_.reset();
  user_data_.reset();
  scan_angle_[0].reset();
  scan_angle_[1].reset();
  for (IntegerCompressor* ic : {&intensity_, &source_, &dx_, &dy_, &z_})
    ic->reset();
  std::memcpy(last_, first, 20);
  // The intensity is predicted per return context from last_intensity_, which starts at 0.
  las::put<std::uint16_t>(last_ + kIntensity, 0);
}

void
Point10CoderV2::decodeChangedFields(ArithmeticDecoder& dec, std::uint32_t changed)
{
  if (changed & kReturnsChanged)
    last_[kReturns] = static_cast<std::uint8_t>(dec.decodeSymbol(returns_.at(last_[kReturns])));
  const std::uint32_t m = point10ReturnContext(numberOfReturns(last_), returnNumber(last_));
  if (changed & kIntensityChanged) {
    const auto v = static_cast<std::uint16_t>(intensity_.decompress(dec, last_intensity_[m], m < 3 ? m : 3));
    last_intensity_[m] = v;
  }
  las::put<std::uint16_t>(last_ + kIntensity, last_intensity_[m]);
  if (changed & kClassChanged)
    last_[kClass] = static_cast<std::uint8_t>(dec.decodeSymbol(class_.at(last_[kClass])));
  if (changed & kAngleChanged) {
    const std::uint32_t d = dec.decodeSymbol(scan_angle_[scanDirection(last_)]);
    last_[kScanAngle] = foldByte(static_cast<int>(d + last_[kScanAngle]));
  }
  if (changed & kUserChanged)
    last_[kUserData] = static_cast<std::uint8_t>(dec.decodeSymbol(user_data_.at(last_[kUserData])));
  if (changed & kSourceChanged) {
    const std::int32_t prev = las::get<std::uint16_t>(last_ + kSource);
    las::put<std::uint16_t>(last_ + kSource, static_cast<std::uint16_t>(source_.decompress(dec, prev)));
  }
}

void
Point10CoderV2::decodeCoordinates(ArithmeticDecoder& dec, std::uint32_t n, std::uint32_t m, std::uint32_t l)
{
  const std::int32_t dx = dx_.decompress(dec, median_dx_[m].get(), n == 1);
  las::put<std::int32_t>(last_ + kX, wrapAdd(las::get<std::int32_t>(last_ + kX), dx));
  median_dx_[m].add(dx);

  const std::int32_t dy = dy_.decompress(dec, median_dy_[m].get(), yContext(n, dx_.k()));
  las::put<std::int32_t>(last_ + kY, wrapAdd(las::get<std::int32_t>(last_ + kY), dy));
  median_dy_[m].add(dy);

  const std::uint32_t k_xy = (dx_.k() + dy_.k()) / 2;
  last_height_[l] = z_.decompress(dec, last_height_[l], zContext(n, k_xy));
  las::put<std::int32_t>(last_ + kZ, last_height_[l]);
}

bool
Point10CoderV2::decode(ArithmeticDecoder& dec, std::uint8_t* out)
{
  const std::uint32_t changed = dec.decodeSymbol(changed_);
  if (changed != 0)
    decodeChangedFields(dec, changed);
  const std::uint32_t n = numberOfReturns(last_), r = returnNumber(last_);
  decodeCoordinates(dec, n, point10ReturnContext(n, r), returnLevel(n, r));
  std::memcpy(out, last_, 20);
  return true;
}

void
Point10CoderV2::encode(ArithmeticEncoder& enc, const std::uint8_t* item)
{
  const std::uint32_t n = numberOfReturns(item), r = returnNumber(item);
  const std::uint32_t m = point10ReturnContext(n, r), l = returnLevel(n, r);
  const std::uint16_t intensity = las::get<std::uint16_t>(item + kIntensity);
  const std::uint16_t source = las::get<std::uint16_t>(item + kSource);
  const std::uint16_t last_source = las::get<std::uint16_t>(last_ + kSource);
  const std::uint32_t changed = (last_[kReturns] != item[kReturns] ? kReturnsChanged : 0) |
                                (last_intensity_[m] != intensity ? kIntensityChanged : 0) |
                                (last_[kClass] != item[kClass] ? kClassChanged : 0) |
                                (last_[kScanAngle] != item[kScanAngle] ? kAngleChanged : 0) |
                                (last_[kUserData] != item[kUserData] ? kUserChanged : 0) |
                                (last_source != source ? kSourceChanged : 0);
  enc.encodeSymbol(changed_, changed);
  if (changed & kReturnsChanged)
    enc.encodeSymbol(returns_.at(last_[kReturns]), item[kReturns]);
  if (changed & kIntensityChanged) {
    intensity_.compress(enc, last_intensity_[m], intensity, m < 3 ? m : 3);
    last_intensity_[m] = intensity;
  }
  if (changed & kClassChanged)
    enc.encodeSymbol(class_.at(last_[kClass]), item[kClass]);
  if (changed & kAngleChanged)
    enc.encodeSymbol(scan_angle_[scanDirection(item)], foldByte(item[kScanAngle] - last_[kScanAngle]));
  if (changed & kUserChanged)
    enc.encodeSymbol(user_data_.at(last_[kUserData]), item[kUserData]);
  if (changed & kSourceChanged)
    source_.compress(enc, last_source, source);

  const std::int32_t dx =
      static_cast<std::int32_t>(las::get<std::uint32_t>(item + kX) - las::get<std::uint32_t>(last_ + kX));
  dx_.compress(enc, median_dx_[m].get(), dx, n == 1);
  median_dx_[m].add(dx);
  const std::int32_t dy =
      static_cast<std::int32_t>(las::get<std::uint32_t>(item + kY) - las::get<std::uint32_t>(last_ + kY));
  dy_.compress(enc, median_dy_[m].get(), dy, yContext(n, dx_.k()));
  median_dy_[m].add(dy);
  const std::int32_t z = las::get<std::int32_t>(item + kZ);
  z_.compress(enc, last_height_[l], z, zContext(n, (dx_.k() + dy_.k()) / 2));
  last_height_[l] = z;
  std::memcpy(last_, item, 20);
}

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makePoint10CoderV2()
{
  return std::make_unique<Point10CoderV2>();
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
