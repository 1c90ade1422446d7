/// \file byte14_coder.cpp
/// \brief The BYTE14 item of layered chunks (extra bytes): one layer per byte, each coding the
///        byte's change from its last value in the same scanner channel.

#include "layered_items.h"

#include <algorithm>

namespace pcl_ls3d {
namespace io {
namespace laz {

namespace {

struct Byte14Context
{
  bool in_use = false;
  std::vector<std::uint8_t> last;
  std::vector<SymbolModel> models;  ///< one per byte, 256 symbols (the change mod 256)
};

/// Starts `c` from the `count` last bytes `from`.
void
startContext(Byte14Context& c, const std::uint8_t* from, std::size_t count)
{
  if (c.models.size() != count)
    c.models.assign(count, SymbolModel(256));
  else
    for (SymbolModel& m : c.models)
      m.reset();
  c.last.assign(from, from + count);
  c.in_use = true;
}

// ------------------------------------------------------------------------------------------
class Byte14Decoder final : public LayeredItemDecoder
{
public:
  Byte14Decoder(std::size_t count, ContextSwitch rule)
      : count_(count), rule_(rule), dec_(count), present_(count, 0)
  {}

  std::size_t
  layerCount() const override
  {
    return count_;
  }

  void
  start(const std::uint8_t* first, const Layer* layers, unsigned& channel) override
  {
    for (std::size_t i = 0; i < count_; ++i) {
      present_[i] = layers[i].size != 0;
      if (present_[i])
        dec_[i].start(layers[i].data, layers[i].data + layers[i].size);
    }
    for (Byte14Context& c : contexts_)
      c.in_use = false;
    current_ = channel & 3;
    startContext(contexts_[current_], first, count_);
  }

  void
  decode(std::uint8_t* item, unsigned& channel) override
  {
    std::uint8_t* last =
        switchChannel(contexts_, current_, channel, rule_,
                      [this](Byte14Context& c, const std::uint8_t* from) { startContext(c, from, count_); });
    Byte14Context& c = contexts_[current_];
    for (std::size_t i = 0; i < count_; ++i) {
      if (present_[i])
        last[i] = static_cast<std::uint8_t>(last[i] + dec_[i].decodeSymbol(c.models[i]));
      item[i] = last[i];
    }
  }

  std::size_t
  overrun() const override
  {
    std::size_t n = 0;
    for (std::size_t i = 0; i < count_; ++i)
      if (present_[i])
        n += dec_[i].overrun();
    return n;
  }

private:
  std::size_t count_;
  ContextSwitch rule_;
  std::vector<ArithmeticDecoder> dec_;
  std::vector<char> present_;
  std::array<Byte14Context, kChannels> contexts_;
  unsigned current_ = 0;
};

// ------------------------------------------------------------------------------------------
class Byte14Encoder final : public LayeredItemEncoder
{
public:
  Byte14Encoder(std::size_t count, ContextSwitch rule)
      : count_(count), rule_(rule), enc_(count), changed_(count, 0)
  {}

  std::size_t
  layerCount() const override
  {
    return count_;
  }

  void
  start(const std::uint8_t* first, unsigned& channel) override
  {
    for (ArithmeticEncoder& e : enc_)
      e.start();
    std::fill(changed_.begin(), changed_.end(), 0);
    for (Byte14Context& c : contexts_)
      c.in_use = false;
    current_ = channel & 3;
    startContext(contexts_[current_], first, count_);
  }

  void
  encode(const std::uint8_t* item, unsigned& channel) override
  {
    std::uint8_t* last =
        switchChannel(contexts_, current_, channel, rule_,
                      [this](Byte14Context& c, const std::uint8_t* from) { startContext(c, from, count_); });
    Byte14Context& c = contexts_[current_];
    for (std::size_t i = 0; i < count_; ++i) {
      enc_[i].encodeSymbol(c.models[i], static_cast<std::uint8_t>(item[i] - last[i]));
      changed_[i] |= item[i] != last[i];
      last[i] = item[i];
    }
  }

  void
  finish(std::vector<std::uint8_t>* layers) override
  {
    for (std::size_t i = 0; i < count_; ++i)
      layers[i] = changed_[i] ? enc_[i].finish() : std::vector<std::uint8_t>();
  }

private:
  std::size_t count_;
  ContextSwitch rule_;
  std::vector<ArithmeticEncoder> enc_;
  std::vector<char> changed_;
  std::array<Byte14Context, kChannels> contexts_;
  unsigned current_ = 0;
};

}  // namespace

std::unique_ptr<LayeredItemDecoder>
makeByte14Decoder(std::size_t count, ContextSwitch rule)
{
  return std::make_unique<Byte14Decoder>(count, rule);
}

std::unique_ptr<LayeredItemEncoder>
makeByte14Encoder(std::size_t count, ContextSwitch rule)
{
  return std::make_unique<Byte14Encoder>(count, rule);
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
