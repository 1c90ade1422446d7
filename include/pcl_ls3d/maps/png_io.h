#pragma once
/// \file png_io.h
/// \brief PNG files of an Image through libpng (8-bit RGB). readPng exists so tests and tools
///        can check what was written.

#include <pcl_ls3d/maps/image.h>

#include <string>

namespace pcl_ls3d {
namespace maps {

/// Writes an 8-bit RGB PNG; false with a one-line reason.
bool
writePng(const std::string& path, const Image& image, std::string& error);

/// Reads an 8-bit RGB or RGBA PNG (alpha dropped; palettes and grey expanded); false with a
/// one-line reason.
bool
readPng(const std::string& path, Image& image, std::string& error);

}  // namespace maps
}  // namespace pcl_ls3d
