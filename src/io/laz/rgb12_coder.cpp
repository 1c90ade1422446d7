/// \file rgb12_coder.cpp
/// \brief RGB12: the red, green, blue words of point formats 2, 3 and 5.
///
/// Version 1 codes each changed byte against its previous value. Version 2 adds that colour
/// channels move together: green is predicted from its previous value plus red's change, blue
/// from the mean change of red and green, and a grey record (all three equal) costs one symbol.

#include "integer_compressor.h"
#include "pointwise_items.h"

#include "io/las_format.h"

#include <cstring>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

/// Low (0) or high (1) byte of channel c (0 red, 1 green, 2 blue) of a 6-byte RGB item.
int
channelByte(const std::uint8_t* rgb, int c, int high)
{
  return rgb[2 * c + high];
}

class Rgb12CoderV1 final : public PointwiseItemCoder
{
public:
  void
  init(const std::uint8_t* first) override
  {
    used_.reset();
    ic_.reset();
    std::memcpy(last_, first, 6);
  }

  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override
  {
    // Bit 2c + h of the symbol: byte h of channel c changed; each byte has its own context.
    const std::uint32_t sym = dec.decodeSymbol(used_);
    for (std::uint32_t b = 0; b < 6; ++b)
      last_[b] = (sym & (1u << b)) ? static_cast<std::uint8_t>(ic_.decompress(dec, last_[b], b)) : last_[b];
    std::memcpy(out, last_, 6);
    return true;
  }

  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override
  {
    std::uint32_t sym = 0;
    for (std::uint32_t b = 0; b < 6; ++b)
      sym |= (item[b] != last_[b]) ? (1u << b) : 0u;
    enc.encodeSymbol(used_, sym);
    for (std::uint32_t b = 0; b < 6; ++b)
      if (sym & (1u << b))
        ic_.compress(enc, last_[b], item[b], b);
    std::memcpy(last_, item, 6);
  }

private:
  std::uint8_t last_[6] = {};
  SymbolModel used_{64};
  IntegerCompressor ic_{8, 6};
};

class Rgb12CoderV2 final : public PointwiseItemCoder
{
public:
  void
  init(const std::uint8_t* first) override
  {
    used_.reset();
    for (SymbolModel& m : diff_)
      m.reset();
    std::memcpy(last_, first, 6);
  }

  bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) override;
  void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) override;

private:
  // Symbol bits: 0/1 red low/high byte changed, 2/3 green, 4/5 blue, 6 not grey.
  static constexpr std::uint32_t kNotGrey = 1u << 6;
  static std::uint32_t
  changedBit(int channel, int high)
  {
    return 1u << (2 * channel + high);
  }

  /// Decodes byte `high` of green and blue (not grey): predictions from red's change.
  void
  decodeGreenBlue(ArithmeticDecoder& dec, std::uint32_t sym, int high, std::uint8_t* rgb);
  void
  encodeGreenBlue(ArithmeticEncoder& enc, std::uint32_t sym, int high, const std::uint8_t* rgb);

  std::uint8_t last_[6] = {};
  SymbolModel used_{128};
  // diff_[2c + h]: the correction of byte h of channel c.
  SymbolModel diff_[6] = {SymbolModel(256), SymbolModel(256), SymbolModel(256),
                          SymbolModel(256), SymbolModel(256), SymbolModel(256)};
};

void
Rgb12CoderV2::decodeGreenBlue(ArithmeticDecoder& dec, std::uint32_t sym, int high, std::uint8_t* rgb)
{
  int change = channelByte(rgb, 0, high) - channelByte(last_, 0, high);
  std::uint8_t& green = rgb[2 + high];
  green = last_[2 + high];
  if (sym & changedBit(1, high)) {
    const int pred = clampByte(change + last_[2 + high]);
    green = foldByte(static_cast<int>(dec.decodeSymbol(diff_[2 + high])) + pred);
  }
  std::uint8_t& blue = rgb[4 + high];
  blue = last_[4 + high];
  if (sym & changedBit(2, high)) {
    change = (change + (green - last_[2 + high])) / 2;
    const int pred = clampByte(change + last_[4 + high]);
    blue = foldByte(static_cast<int>(dec.decodeSymbol(diff_[4 + high])) + pred);
  }
}

bool
Rgb12CoderV2::decode(ArithmeticDecoder& dec, std::uint8_t* out)
{
  const std::uint32_t sym = dec.decodeSymbol(used_);
  std::uint8_t rgb[6];
  for (int high = 0; high < 2; ++high) {
    rgb[high] = last_[high];
    if (sym & changedBit(0, high))
      rgb[high] = foldByte(static_cast<int>(dec.decodeSymbol(diff_[high])) + last_[high]);
  }
  if (sym & kNotGrey) {
    decodeGreenBlue(dec, sym, 0, rgb);
    decodeGreenBlue(dec, sym, 1, rgb);
  } else {
    std::memcpy(rgb + 2, rgb, 2);
    std::memcpy(rgb + 4, rgb, 2);
  }
  std::memcpy(last_, rgb, 6);
  std::memcpy(out, rgb, 6);
  return true;
}

void
Rgb12CoderV2::encodeGreenBlue(ArithmeticEncoder& enc, std::uint32_t sym, int high, const std::uint8_t* rgb)
{
  // Red's change counts only when its byte changed (else it is 0 either way).
  int change = (sym & changedBit(0, high)) ? rgb[high] - last_[high] : 0;
  if (sym & changedBit(1, high)) {
    const int pred = clampByte(change + last_[2 + high]);
    enc.encodeSymbol(diff_[2 + high], foldByte(rgb[2 + high] - pred));
  }
  if (sym & changedBit(2, high)) {
    change = (change + rgb[2 + high] - last_[2 + high]) / 2;
    const int pred = clampByte(change + last_[4 + high]);
    enc.encodeSymbol(diff_[4 + high], foldByte(rgb[4 + high] - pred));
  }
}

void
Rgb12CoderV2::encode(ArithmeticEncoder& enc, const std::uint8_t* item)
{
  std::uint32_t sym = 0;
  for (int b = 0; b < 6; ++b)
    sym |= (item[b] != last_[b]) ? (1u << b) : 0u;
  const bool grey = std::memcmp(item, item + 2, 2) == 0 && std::memcmp(item, item + 4, 2) == 0;
  sym |= grey ? 0u : kNotGrey;
  enc.encodeSymbol(used_, sym);
  for (int high = 0; high < 2; ++high)
    if (sym & changedBit(0, high))
      enc.encodeSymbol(diff_[high], foldByte(item[high] - last_[high]));
  if (sym & kNotGrey) {
    // LASzip's order: green and blue low bytes, then green and blue high bytes.
    encodeGreenBlue(enc, sym, 0, item);
    encodeGreenBlue(enc, sym, 1, item);
  }
  std::memcpy(last_, item, 6);
}

}  // namespace

std::unique_ptr<PointwiseItemCoder>
makeRgb12Coder(int version)
{
  if (version == 1)
    return std::make_unique<Rgb12CoderV1>();
  return std::make_unique<Rgb12CoderV2>();
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
