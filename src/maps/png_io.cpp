#include <pcl_ls3d/maps/png_io.h>

#include <png.h>

#include <cstdio>
#include <memory>
#include <vector>

namespace pcl_ls3d {
namespace maps {

namespace {

struct FileCloser
{
  void
  operator()(std::FILE* f) const
  {
    if (f)
      std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through longjmp; the message is kept here for the caller.
void
onPngError(png_structp png, png_const_charp message)
{
  auto* error = static_cast<std::string*>(png_get_error_ptr(png));
  if (error)
    *error = message;
  png_longjmp(png, 1);
}

void
onPngWarning(png_structp, png_const_charp)
{}

}  // namespace

bool
writePng(const std::string& path, const Image& image, std::string& error)
{
  if (image.empty()) {
    error = "cannot write an empty image to " + path;
    return false;
  }
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) {
    error = "cannot open " + path + " for writing";
    return false;
  }
  std::string png_error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &png_error, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    error = "libpng could not be initialised";
    return false;
  }
  std::vector<png_const_bytep> rows(static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y)
    rows[static_cast<std::size_t>(y)] =
        image.pixels().data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width()) * 3;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    error = "cannot write " + path + ": " + png_error;
    return false;
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width()), static_cast<png_uint_32>(image.height()),
               8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, const_cast<png_bytepp>(rows.data()));
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(file.get()) != 0) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

bool
readPng(const std::string& path, Image& image, std::string& error)
{
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    error = "cannot open " + path;
    return false;
  }
  unsigned char signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    error = path + " is not a PNG file";
    return false;
  }
  std::string png_error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &png_error, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    error = "libpng could not be initialised";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    error = "cannot read " + path + ": " + png_error;
    return false;
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_png(png, info,
               PNG_TRANSFORM_STRIP_16 | PNG_TRANSFORM_PACKING | PNG_TRANSFORM_EXPAND |
                   PNG_TRANSFORM_GRAY_TO_RGB | PNG_TRANSFORM_STRIP_ALPHA,
               nullptr);
  const int w = static_cast<int>(png_get_image_width(png, info));
  const int h = static_cast<int>(png_get_image_height(png, info));
  const png_bytepp rows = png_get_rows(png, info);
  image = Image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const png_bytep p = rows[y] + 3 * x;
      image.set(x, y, {p[0], p[1], p[2]});
    }
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace maps
}  // namespace pcl_ls3d
