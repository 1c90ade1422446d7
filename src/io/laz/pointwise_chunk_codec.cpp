/// \file pointwise_chunk_codec.cpp
/// \brief Placeholder until the pointwise item coders land: refuses with one line.

#include "laszip_items.h"

namespace pcl_ls3d {
namespace io {
namespace laz {

std::unique_ptr<ChunkDecoder>
makePointwiseChunkDecoder(const LaszipVlr&, std::string& error)
{
  error = "pointwise LAZ decoding is not implemented yet";
  return nullptr;
}

std::unique_ptr<ChunkEncoder>
makePointwiseChunkEncoder(const LaszipVlr&, std::string& error)
{
  error = "pointwise LAZ encoding is not implemented yet";
  return nullptr;
}

}  // namespace laz
}  // namespace io
}  // namespace pcl_ls3d
