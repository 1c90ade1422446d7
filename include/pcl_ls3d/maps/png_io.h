#pragma once
/// \file png_io.h
/// \brief PNG files of an Image through cairo (8-bit RGB): the plain pictures that are no
///        Drawing, and readPng so that tests and tools can check what was written.

#include <pcl_ls3d/maps/image.h>

#include <string>

namespace pcl_ls3d {
namespace maps {

/// Writes an 8-bit RGB PNG (replacing \a path; callers check first); false with a one-line
/// reason, no partial file left.
bool
writePng(const std::string& path, const Image& image, std::string& error);

/// Reads a PNG (alpha dropped; palettes, grey and 16 bits converted as cairo does); false with a
/// one-line reason.
bool
readPng(const std::string& path, Image& image, std::string& error);

}  // namespace maps
}  // namespace pcl_ls3d
