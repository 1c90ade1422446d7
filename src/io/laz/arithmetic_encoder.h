#pragma once
/// \file arithmetic_encoder.h
/// \brief Private: the LASzip arithmetic encoder, appending to a byte vector (one per chunk, or
///        one per layer of a layered chunk). finish() flushes the interval the way LASzip does,
///        so a LASzip decoder reads exactly the symbols written.

#include "arithmetic_models.h"

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace io {
namespace laz {

class ArithmeticEncoder
{
public:
  /// Starts a new stream (the bytes written so far are discarded).
  void
  start()
  {
    out_.clear();
    base_ = 0;
    length_ = kMaxLength;
  }

  void
  encodeBit(BitModel& m, std::uint32_t sym)
  {
    const std::uint32_t x = m.bit_0_prob * (length_ >> kBitLengthShift);
    if (sym == 0) {
      length_ = x;
      ++m.bit_0_count;
    } else {
      add(x);
      length_ -= x;
    }
    if (length_ < kMinLength)
      renormalise();
    if (--m.bits_until_update == 0)
      m.update();
  }

  void
  encodeSymbol(SymbolModel& m, std::uint32_t sym)
  {
    if (sym == m.last_symbol) {
      const std::uint32_t x = m.distribution[sym] * (length_ >> kSymbolLengthShift);
      add(x);
      length_ -= x;
    } else {
      const std::uint32_t x = m.distribution[sym] * (length_ >>= kSymbolLengthShift);
      add(x);
      length_ = m.distribution[sym + 1] * length_ - x;
    }
    if (length_ < kMinLength)
      renormalise();
    ++m.symbol_count[sym];
    if (--m.symbols_until_update == 0)
      m.update();
  }

  void
  writeBit(std::uint32_t sym)
  {
    add(sym * (length_ >>= 1));
    if (length_ < kMinLength)
      renormalise();
  }

  /// The low `bits` (1–32) bits of sym.
  void
  writeBits(std::uint32_t bits, std::uint32_t sym)
  {
    if (bits > 19) {
      writeShort(sym & 0xFFFFu);
      sym >>= 16;
      bits -= 16;
    }
    add(sym * (length_ >>= bits));
    if (length_ < kMinLength)
      renormalise();
  }

  void
  writeShort(std::uint32_t sym)
  {
    add(sym * (length_ >>= 16));
    if (length_ < kMinLength)
      renormalise();
  }

  void
  writeInt(std::uint32_t sym)
  {
    writeShort(sym & 0xFFFFu);
    writeShort(sym >> 16);
  }

  void
  writeInt64(std::uint64_t sym)
  {
    writeInt(static_cast<std::uint32_t>(sym));
    writeInt(static_cast<std::uint32_t>(sym >> 32));
  }

  /// Flushes the interval and returns the stream's bytes.
  const std::vector<std::uint8_t>&
  finish();

  /// The bytes written so far (before finish(): without the flush).
  const std::vector<std::uint8_t>&
  bytes() const
  {
    return out_;
  }

private:
  /// base += x, carrying into the bytes already written when base wraps.
  void
  add(std::uint32_t x)
  {
    const std::uint32_t before = base_;
    base_ += x;
    if (before > base_)
      propagateCarry();
  }

  void
  propagateCarry();
  void
  renormalise()
  {
    do {
      out_.push_back(static_cast<std::uint8_t>(base_ >> 24));
      base_ <<= 8;
    } while ((length_ <<= 8) < kMinLength);
  }

  std::vector<std::uint8_t> out_;
  std::uint32_t base_ = 0, length_ = kMaxLength;
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
