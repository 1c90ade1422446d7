// PNG files through cairo's PNG reader and writer (libpng underneath, inside cairo).
#include <pcl_ls3d/maps/png_io.h>

#include "cairo_file.h"
#include "cairo_image.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace pcl_ls3d {
namespace maps {

namespace {

cairo_status_t
readFromFile(void* closure, unsigned char* data, unsigned int length)
{
  return std::fread(data, 1, length, static_cast<std::FILE*>(closure)) == length ? CAIRO_STATUS_SUCCESS
                                                                                 : CAIRO_STATUS_READ_ERROR;
}

struct FileCloser
{
  void
  operator()(std::FILE* f) const
  {
    std::fclose(f);
  }
};

bool
hasPngSignature(std::FILE* f)
{
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8] = {};
  const bool ok = std::fread(head, 1, 8, f) == 8 && std::memcmp(head, kSignature, 8) == 0;
  std::rewind(f);
  return ok;
}

}  // namespace

bool
writePng(const std::string& path, const Image& image, std::string& error)
{
  if (image.empty())
    return (error = "cannot write an empty image to " + path).empty();
  detail::OutputFile file(path, true);
  if (!file.isOpen())
    return (error = file.openError()).empty();
  cairo_surface_t* surface = detail::surfaceOf(image);
  cairo_status_t status = cairo_surface_status(surface);
  if (status == CAIRO_STATUS_SUCCESS)
    status = cairo_surface_write_to_png_stream(surface, &detail::OutputFile::write, &file);
  cairo_surface_destroy(surface);
  return file.commit(status, error);
}

bool
readPng(const std::string& path, Image& image, std::string& error)
{
  errno = 0;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file)
    return (error = "cannot open " + path + ": " + std::strerror(errno ? errno : ENOENT)).empty();
  if (!hasPngSignature(file.get()))
    return (error = path + " is not a PNG file").empty();
  cairo_surface_t* surface = cairo_image_surface_create_from_png_stream(&readFromFile, file.get());
  const cairo_status_t status = cairo_surface_status(surface);
  if (status == CAIRO_STATUS_SUCCESS)
    image = detail::imageOf(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    return (error = "cannot read " + path + ": " + cairo_status_to_string(status)).empty();
  return true;
}

}  // namespace maps
}  // namespace pcl_ls3d
