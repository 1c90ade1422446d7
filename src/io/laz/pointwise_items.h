#pragma once
/// \file pointwise_items.h
/// \brief Private: the item coders of LASzip's pointwise compressors (point formats 0–5). A record
///        is a row of items (POINT10, then GPSTIME11, RGB12, BYTE as the format has them); each
///        item has its own coder that predicts the item from the previous record of the chunk and
///        codes what the prediction missed. A chunk's first record is stored raw and starts every
///        coder (init); the following records go through decode / encode.

#include "arithmetic_decoder.h"
#include "arithmetic_encoder.h"

#include <array>
#include <cstdint>
#include <memory>

namespace pcl_ls3d {
namespace io {
namespace laz {

/// \brief The coder of one item of a point record, for one chunk at a time.
class PointwiseItemCoder
{
public:
  virtual ~PointwiseItemCoder() = default;
  /// Starts a chunk whose first record holds `first` for this item: every model back to its
  /// initial state, the prediction from `first`.
  virtual void
  init(const std::uint8_t* first) = 0;
  /// Decodes this item of the next record into `out`. False when the stream holds a code that no
  /// encoder writes (the chunk is corrupt).
  virtual bool
  decode(ArithmeticDecoder& dec, std::uint8_t* out) = 0;
  /// Encodes this item of the next record.
  virtual void
  encode(ArithmeticEncoder& enc, const std::uint8_t* item) = 0;
};

// One factory per item (point10_coder_v1.cpp, point10_coder_v2.cpp, gpstime11_coder_v1.cpp,
// gpstime11_coder_v2.cpp, rgb12_coder.cpp, byte_coder.cpp). `version` is 1 or 2.
std::unique_ptr<PointwiseItemCoder>
makePoint10CoderV1();
std::unique_ptr<PointwiseItemCoder>
makePoint10CoderV2();
std::unique_ptr<PointwiseItemCoder>
makeGpsTime11CoderV1();
std::unique_ptr<PointwiseItemCoder>
makeGpsTime11CoderV2();
std::unique_ptr<PointwiseItemCoder>
makeRgb12Coder(int version);
std::unique_ptr<PointwiseItemCoder>
makeByteCoder(int version, std::size_t bytes);

// ---- small pieces the item coders share ---------------------------------------------------

/// A byte difference or sum taken modulo 256 (what LASzip calls folding).
inline std::uint8_t
foldByte(int v)
{
  return static_cast<std::uint8_t>(v & 0xFF);
}

/// A prediction clamped to a byte.
inline int
clampByte(int v)
{
  return v < 0 ? 0 : (v > 255 ? 255 : v);
}

/// 32-bit wrap-around sum (the format's coordinates wrap; signed overflow would be undefined).
inline std::int32_t
wrapAdd(std::int32_t a, std::int32_t b)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

inline std::int32_t
wrapMul(std::int32_t a, std::int32_t b)
{
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) * static_cast<std::uint32_t>(b));
}

/// C's conversion to int as the x86 LASzip builds perform it: truncation, and INT32_MIN for a
/// value outside the int range (so an encoder picks the same multiplier branch as LASzip).
inline std::int32_t
truncateToInt(double v)
{
  if (!(v > -2147483649.0 && v < 2147483648.0))
    return INT32_MIN;
  return static_cast<std::int32_t>(v);
}

/// \brief 256 adaptive byte models, one per value of a context byte, created when first used
///        (most contexts never occur; a model is some kilobytes).
class ByteModelsByContext
{
public:
  SymbolModel&
  at(std::uint8_t context)
  {
    std::unique_ptr<SymbolModel>& m = models_[context];
    if (!m)
      m = std::make_unique<SymbolModel>(256);
    return *m;
  }

  /// As at the start of a chunk: a model created earlier restarts from its initial state.
  void
  reset()
  {
    for (std::unique_ptr<SymbolModel>& m : models_)
      if (m)
        m->reset();
  }

private:
  std::array<std::unique_ptr<SymbolModel>, 256> models_;
};

/// \brief The median of the last five values, kept sorted. LASzip's "streaming median": each new
///        value replaces the largest or the smallest, alternating by where the values fall, so it
///        is not the exact median of the last five; encoder and decoder must agree, so it is
///        reproduced as the format defines it.
class StreamingMedian5
{
public:
  void
  reset()
  {
    v_.fill(0);
    drop_largest_ = true;
  }

  std::int32_t
  get() const
  {
    return v_[2];
  }

  void
  add(std::int32_t x);

private:
  std::array<std::int32_t, 5> v_{};
  bool drop_largest_ = true;
};

/// Context of a record's coordinates by its return number r and number of returns n (0–7 each):
/// the sensible (n, r) pairs get contexts 0–14, the rest share the upper ones (LASzip's table).
std::uint32_t
point10ReturnContext(std::uint32_t n, std::uint32_t r);

/// Which earlier height predicts a record's z: |n − r|, the distance from the last return.
inline std::uint32_t
returnLevel(std::uint32_t n, std::uint32_t r)
{
  return n > r ? n - r : r - n;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
