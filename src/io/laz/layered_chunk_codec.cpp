/// \file layered_chunk_codec.cpp
/// \brief Placeholder until the layered item coders land: refuses with one line.

#include "laszip_items.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

std::unique_ptr<ChunkDecoder>
makeLayeredChunkDecoder(const LaszipVlr&, std::string& error)
{
  error = "layered LAZ decoding is not implemented yet";
  return nullptr;
}

std::unique_ptr<ChunkEncoder>
makeLayeredChunkEncoder(const LaszipVlr&, std::string& error)
{
  error = "layered LAZ encoding is not implemented yet";
  return nullptr;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
