/// \file point10_coder_v1.cpp
/// \brief POINT10 version 1, as the first LASzip releases wrote it: X and Y against the median of
///        the last three differences, Z against the previous Z, then a six-bit symbol saying which
///        other fields changed, each coded against its previous value.

#include "integer_compressor.h"
#include "pointwise_items.h"

#include "io/las_format.h"

#include <algorithm>
#include <cstring>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

constexpr std::size_t kX = 0, kY = 4, kZ = 8, kIntensity = 12, kReturns = 14, kClass = 15, kScanAngle = 16,
                      kUserData = 17, kSource = 18;
constexpr std::uint32_t kIntensityChanged = 32, kReturnsChanged = 16, kClassChanged = 8, kAngleChanged = 4,
                        kUserChanged = 2, kSourceChanged = 1;

std::int32_t
median3(const std::int32_t v[3])
{
  return std::max(std::min(v[0], v[1]), std::min(std::max(v[0], v[1]), v[2]));
}

/// Context of Y (from the bits X needed) and of Z (from the mean of X's and Y's).
std::uint32_t
bitsContext(std::uint32_t k)
{
  return k < 19 ? k : 19;
}

class Point10CoderV1 final : public PointwiseItemCoder
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
  decodeChangedFields(ArithmeticDecoder& dec, std::uint32_t changed, std::uint32_t k_xy);
  void
  encodeChangedFields(ArithmeticEncoder& enc, const std::uint8_t* item, std::uint32_t k_xy);
  void
  rememberDifferences(std::int32_t dx, std::int32_t dy);

  std::uint8_t last_[20] = {};
  std::int32_t last_dx_[3] = {}, last_dy_[3] = {};
  int next_slot_ = 0;

  SymbolModel changed_{64};
  ByteModelsByContext returns_, class_, user_data_;
  IntegerCompressor dx_{32}, dy_{32, 20}, z_{32, 20}, intensity_{16}, scan_angle_{8, 2}, source_{16};
};

void
Point10CoderV1::init(const std::uint8_t* first)
{
  std::fill(std::begin(last_dx_), std::end(last_dx_), 0);
  std::fill(std::begin(last_dy_), std::end(last_dy_), 0);
  next_slot_ = 0;
  changed_.reset();
  returns_.reset();
  class_.reset();
  user_data_.reset();
  for (IntegerCompressor* ic : {&dx_, &dy_, &z_, &intensity_, &scan_angle_, &source_})
    ic->reset();
  std::memcpy(last_, first, 20);
}

void
Point10CoderV1::rememberDifferences(std::int32_t dx, std::int32_t dy)
{
  last_dx_[next_slot_] = dx;
  last_dy_[next_slot_] = dy;
  next_slot_ = (next_slot_ + 1) % 3;
}

void
Point10CoderV1::decodeChangedFields(ArithmeticDecoder& dec, std::uint32_t changed, std::uint32_t k_xy)
{
  if (changed & kIntensityChanged) {
    const std::int32_t prev = las::get<std::uint16_t>(last_ + kIntensity);
    las::put<std::uint16_t>(last_ + kIntensity, static_cast<std::uint16_t>(intensity_.decompress(dec, prev)));
  }
  if (changed & kReturnsChanged)
    last_[kReturns] = static_cast<std::uint8_t>(dec.decodeSymbol(returns_.at(last_[kReturns])));
  if (changed & kClassChanged)
    last_[kClass] = static_cast<std::uint8_t>(dec.decodeSymbol(class_.at(last_[kClass])));
  if (changed & kAngleChanged)
    last_[kScanAngle] = static_cast<std::uint8_t>(scan_angle_.decompress(dec, last_[kScanAngle], k_xy < 3));
  if (changed & kUserChanged)
    last_[kUserData] = static_cast<std::uint8_t>(dec.decodeSymbol(user_data_.at(last_[kUserData])));
  if (changed & kSourceChanged) {
    const std::int32_t prev = las::get<std::uint16_t>(last_ + kSource);
    las::put<std::uint16_t>(last_ + kSource, static_cast<std::uint16_t>(source_.decompress(dec, prev)));
  }
}

bool
Point10CoderV1::decode(ArithmeticDecoder& dec, std::uint8_t* out)
{
  const std::int32_t dx = dx_.decompress(dec, median3(last_dx_));
  las::put<std::int32_t>(last_ + kX, wrapAdd(las::get<std::int32_t>(last_ + kX), dx));
  const std::uint32_t k_x = dx_.k();
  const std::int32_t dy = dy_.decompress(dec, median3(last_dy_), bitsContext(k_x));
  las::put<std::int32_t>(last_ + kY, wrapAdd(las::get<std::int32_t>(last_ + kY), dy));
  const std::uint32_t k_xy = (k_x + dy_.k()) / 2;
  las::put<std::int32_t>(last_ + kZ,
                         z_.decompress(dec, las::get<std::int32_t>(last_ + kZ), bitsContext(k_xy)));
  const std::uint32_t changed = dec.decodeSymbol(changed_);
  if (changed != 0)
    decodeChangedFields(dec, changed, k_xy);
  rememberDifferences(dx, dy);
  std::memcpy(out, last_, 20);
  return true;
}

void
Point10CoderV1::encodeChangedFields(ArithmeticEncoder& enc, const std::uint8_t* item, std::uint32_t k_xy)
{
  const std::uint16_t intensity = las::get<std::uint16_t>(item + kIntensity);
  const std::uint16_t last_intensity = las::get<std::uint16_t>(last_ + kIntensity);
  const std::uint16_t source = las::get<std::uint16_t>(item + kSource);
  const std::uint16_t last_source = las::get<std::uint16_t>(last_ + kSource);
  const std::uint32_t changed = (last_intensity != intensity ? kIntensityChanged : 0) |
                                (last_[kReturns] != item[kReturns] ? kReturnsChanged : 0) |
                                (last_[kClass] != item[kClass] ? kClassChanged : 0) |
                                (last_[kScanAngle] != item[kScanAngle] ? kAngleChanged : 0) |
                                (last_[kUserData] != item[kUserData] ? kUserChanged : 0) |
                                (last_source != source ? kSourceChanged : 0);
  enc.encodeSymbol(changed_, changed);
  if (changed & kIntensityChanged)
    intensity_.compress(enc, last_intensity, intensity);
  if (changed & kReturnsChanged)
    enc.encodeSymbol(returns_.at(last_[kReturns]), item[kReturns]);
  if (changed & kClassChanged)
    enc.encodeSymbol(class_.at(last_[kClass]), item[kClass]);
  if (changed & kAngleChanged)
    scan_angle_.compress(enc, last_[kScanAngle], item[kScanAngle], k_xy < 3);
  if (changed & kUserChanged)
    enc.encodeSymbol(user_data_.at(last_[kUserData]), item[kUserData]);
  if (changed & kSourceChanged)
    source_.compress(enc, last_source, source);
}

void
Point10CoderV1::encode(ArithmeticEncoder& enc, const std::uint8_t* item)
{
  const std::int32_t dx =
      static_cast<std::int32_t>(las::get<std::uint32_t>(item + kX) - las::get<std::uint32_t>(last_ + kX));
  const std::int32_t dy =
      static_cast<std::int32_t>(las::get<std::uint32_t>(item + kY) - las::get<std::uint32_t>(last_ + kY));
  dx_.compress(enc, median3(last_dx_), dx);
  const std::uint32_t k_x = dx_.k();
  dy_.compress(enc, median3(last_dy_), dy, bitsContext(k_x));
  const std::uint32_t k_xy = (k_x + dy_.k()) / 2;
  z_.compress(enc, las::get<std::int32_t>(last_ + kZ), las::get<std::int32_t>(item + kZ), bitsContext(k_xy));
  encodeChangedFields(enc, item, k_xy);
  rememberDifferences(dx, dy);
  std::memcpy(last_, item, 20);
}

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makePoint10CoderV1()
{
  return std::make_unique<Point10CoderV1>();
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
