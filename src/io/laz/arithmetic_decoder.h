#pragma once
/// \file arithmetic_decoder.h
/// \brief Private: the LASzip arithmetic decoder over one byte range (a chunk, or one layer of a
///        layered chunk). Reading past the range yields zero bytes and counts them, so garbage or
///        truncated input decodes to garbage of bounded size that the caller then refuses; the
///        decoder never reads outside [begin, end).

#include "arithmetic_models.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace pcl_ls3d {
namespace io {
namespace laz {

class ArithmeticDecoder
{
public:
  ArithmeticDecoder() = default;
  ArithmeticDecoder(const std::uint8_t* begin, const std::uint8_t* end)
  {
    start(begin, end);
  }

  /// Starts decoding the range: reads the first four bytes into the interval's value.
  void
  start(const std::uint8_t* begin, const std::uint8_t* end)
  {
    begin_ = next_ = begin;
    end_ = end;
    overrun_ = 0;
    length_ = kMaxLength;
    value_ = 0;
    for (int i = 0; i < 4; ++i)
      value_ = (value_ << 8) | nextByte();
  }

  /// Bytes of the range read so far. Once the last symbol is decoded this is the stream's length:
  /// the encoder's flush ends exactly where the decoder's look-ahead does.
  std::size_t
  consumed() const
  {
    return static_cast<std::size_t>(next_ - begin_);
  }

  /// Bytes requested beyond the range (0 for a well-formed stream).
  std::size_t
  overrun() const
  {
    return overrun_;
  }

  std::uint32_t
  decodeBit(BitModel& m)
  {
    const std::uint32_t x = m.bit_0_prob * (length_ >> kBitLengthShift);
    const std::uint32_t sym = (value_ >= x);
    if (sym == 0) {
      length_ = x;
      ++m.bit_0_count;
    } else {
      value_ -= x;
      length_ -= x;
    }
    if (length_ < kMinLength)
      renormalise();
    if (--m.bits_until_update == 0)
      m.update();
    return sym;
  }

  std::uint32_t
  decodeSymbol(SymbolModel& m)
  {
    std::uint32_t n, sym, x, y = length_;
    if (!m.decoder_table.empty()) {
      const std::uint32_t dv = value_ / (length_ >>= kSymbolLengthShift);
      // A valid stream keeps value_ < length_, so t <= table_size; garbage can push value_
      // past length_ and t past the table, so it is clamped (valid streams are unaffected).
      const std::uint32_t t = std::min(dv >> m.table_shift, m.table_size);
      sym = m.decoder_table[t];
      n = m.decoder_table[t + 1] + 1;
      while (n > sym + 1) {
        const std::uint32_t k = (sym + n) >> 1;
        if (m.distribution[k] > dv)
          n = k;
        else
          sym = k;
      }
      x = m.distribution[sym] * length_;
      if (sym != m.last_symbol)
        y = m.distribution[sym + 1] * length_;
    } else {
      x = sym = 0;
      length_ >>= kSymbolLengthShift;
      n = m.symbols;
      std::uint32_t k = n >> 1;
      do {
        const std::uint32_t z = length_ * m.distribution[k];
        if (z > value_) {
          n = k;
          y = z;
        } else {
          sym = k;
          x = z;
        }
      } while ((k = (sym + n) >> 1) != sym);
    }
    value_ -= x;
    length_ = y - x;
    if (length_ < kMinLength)
      renormalise();
    ++m.symbol_count[sym];
    if (--m.symbols_until_update == 0)
      m.update();
    return sym;
  }

  /// One raw (equiprobable) bit.
  std::uint32_t
  readBit()
  {
    const std::uint32_t sym = value_ / (length_ >>= 1);
    value_ -= length_ * sym;
    if (length_ < kMinLength)
      renormalise();
    return sym;
  }

  /// `bits` raw bits (1–32).
  std::uint32_t
  readBits(std::uint32_t bits)
  {
    if (bits > 19) {
      const std::uint32_t low = readShort();
      return (readBits(bits - 16) << 16) | low;
    }
    const std::uint32_t sym = value_ / (length_ >>= bits);
    value_ -= length_ * sym;
    if (length_ < kMinLength)
      renormalise();
    return sym;
  }

  std::uint32_t
  readShort()
  {
    const std::uint32_t sym = value_ / (length_ >>= 16);
    value_ -= length_ * sym;
    if (length_ < kMinLength)
      renormalise();
    return sym;
  }

  std::uint32_t
  readInt()
  {
    const std::uint32_t low = readShort();
    return (readShort() << 16) | low;
  }

  std::uint64_t
  readInt64()
  {
    const std::uint64_t low = readInt();
    return (static_cast<std::uint64_t>(readInt()) << 32) | low;
  }

private:
  std::uint32_t
  nextByte()
  {
    if (next_ < end_)
      return *next_++;
    ++overrun_;
    return 0;
  }

  void
  renormalise()
  {
    do {
      value_ = (value_ << 8) | nextByte();
    } while ((length_ <<= 8) < kMinLength);
  }

  const std::uint8_t* begin_ = nullptr;
  const std::uint8_t* next_ = nullptr;
  const std::uint8_t* end_ = nullptr;
  std::size_t overrun_ = 0;
  std::uint32_t value_ = 0, length_ = kMaxLength;
};

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
