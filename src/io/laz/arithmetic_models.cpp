/// \file arithmetic_models.cpp
/// \brief The models' adaptation rules; every constant here is fixed by the LASzip format.

#include "arithmetic_models.h"

#include <algorithm>

namespace pcl_ls3d {
namespace io {
namespace laz {

void
BitModel::update()
{
  if ((bit_count += update_cycle) > kBitMaxCount) {
    bit_count = (bit_count + 1) >> 1;
    bit_0_count = (bit_0_count + 1) >> 1;
    if (bit_0_count == bit_count)
      ++bit_count;
  }
  const std::uint32_t scale = 0x80000000u / bit_count;
  bit_0_prob = (bit_0_count * scale) >> (31 - kBitLengthShift);
  update_cycle = std::min<std::uint32_t>((5 * update_cycle) >> 2, 64);
  bits_until_update = update_cycle;
}

SymbolModel::SymbolModel(std::uint32_t n) : symbols(n), last_symbol(n - 1)
{
  if (symbols > 16) {
    std::uint32_t table_bits = 3;
    while (symbols > (1u << (table_bits + 2)))
      ++table_bits;
    table_size = 1u << table_bits;
    table_shift = kSymbolLengthShift - table_bits;
    decoder_table.assign(table_size + 2, 0);
  }
  distribution.assign(symbols, 0);
  symbol_count.assign(symbols, 0);
  reset();
}

void
SymbolModel::reset()
{
  total_count = 0;
  update_cycle = symbols;
  std::fill(symbol_count.begin(), symbol_count.end(), 1u);
  update();
  symbols_until_update = update_cycle = (symbols + 6) >> 1;
}

void
SymbolModel::update()
{
  if ((total_count += update_cycle) > kSymbolMaxCount) {
    total_count = 0;
    for (std::uint32_t n = 0; n < symbols; ++n)
      total_count += (symbol_count[n] = (symbol_count[n] + 1) >> 1);
  }
  const std::uint32_t scale = 0x80000000u / total_count;
  std::uint32_t sum = 0;
  if (table_size == 0) {
    for (std::uint32_t k = 0; k < symbols; ++k) {
      distribution[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += symbol_count[k];
    }
  } else {
    std::uint32_t s = 0;
    for (std::uint32_t k = 0; k < symbols; ++k) {
      distribution[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += symbol_count[k];
      const std::uint32_t w = distribution[k] >> table_shift;
      while (s < w)
        decoder_table[++s] = k - 1;
    }
    decoder_table[0] = 0;
    while (s <= table_size)
      decoder_table[++s] = symbols - 1;
  }
  update_cycle = (5 * update_cycle) >> 2;
  const std::uint32_t max_cycle = (symbols + 6) << 3;
  if (update_cycle > max_cycle)
    update_cycle = max_cycle;
  symbols_until_update = update_cycle;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
