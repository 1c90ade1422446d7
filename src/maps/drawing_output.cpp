// Where a Drawing goes: its recording replayed onto an image (PNG, rasterise()), a PDF page or
// an SVG document.
#include "cairo_file.h"
#include "cairo_image.h"
#include "cairo_text.h"
#include "drawing_recording.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>

namespace pcl_ls3d {
namespace maps {

namespace {

constexpr double kPointsPerPixel = 0.75;  // a pixel at 96 dpi, as browsers and office suites show it

// Replays the recording onto a target surface, scaled; returns cairo's status of the drawing.
cairo_status_t
replay(cairo_surface_t* recording, cairo_surface_t* target, double scale)
{
  cairo_t* cr = cairo_create(target);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, recording, 0.0, 0.0);
  cairo_paint(cr);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  return status;
}

cairo_surface_t*
rasterSurface(cairo_surface_t* recording, int width, int height)
{
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  if (cairo_surface_status(image) == CAIRO_STATUS_SUCCESS)
    replay(recording, image, 1.0);
  return image;
}

// The target surface of a vector format, writing into \a file.
cairo_surface_t*
vectorSurface(MapFormat format, detail::OutputFile& file, int width, int height, const std::string& title)
{
  if (format == MapFormat::SVG) {
    cairo_surface_t* svg =
        cairo_svg_surface_create_for_stream(&detail::OutputFile::write, &file, width, height);
    cairo_svg_surface_set_document_unit(svg, CAIRO_SVG_UNIT_PX);
    return svg;
  }
  cairo_surface_t* pdf = cairo_pdf_surface_create_for_stream(
      &detail::OutputFile::write, &file, width * kPointsPerPixel, height * kPointsPerPixel);
  if (!title.empty())
    cairo_pdf_surface_set_metadata(pdf, CAIRO_PDF_METADATA_TITLE, detail::validUtf8(title).c_str());
  cairo_pdf_surface_set_metadata(pdf, CAIRO_PDF_METADATA_CREATOR, "pcl_ls3d");
  return pdf;
}

}  // namespace

Image
Drawing::rasterise() const
{
  if (empty())
    return Image();
  cairo_surface_t* surface = rasterSurface(recording_->surface, width_, height_);
  Image image = cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS ? detail::imageOf(surface) : Image();
  cairo_surface_destroy(surface);
  return image;
}

bool
Drawing::write(const std::string& path, MapFormat format, std::string& error, bool overwrite) const
{
  if (empty())
    return (error = "nothing to draw into " + path).empty();
  if (cairo_status(recording_->cr) != CAIRO_STATUS_SUCCESS)
    return (error = "cannot draw " + path + ": " + cairo_status_to_string(cairo_status(recording_->cr)))
        .empty();
  detail::OutputFile file(path, overwrite);
  if (!file.isOpen())
    return (error = file.openError()).empty();
  cairo_surface_t* surface = nullptr;
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (format == MapFormat::PNG) {
    surface = rasterSurface(recording_->surface, width_, height_);
    status = cairo_surface_status(surface);
    if (status == CAIRO_STATUS_SUCCESS)
      status = cairo_surface_write_to_png_stream(surface, &detail::OutputFile::write, &file);
  } else {
    surface = vectorSurface(format, file, width_, height_, title_);
    const double scale = format == MapFormat::PDF ? kPointsPerPixel : 1.0;
    status = cairo_surface_status(surface);
    if (status == CAIRO_STATUS_SUCCESS)
      status = replay(recording_->surface, surface, scale);
    cairo_surface_finish(surface);  // writes the document's end
    if (status == CAIRO_STATUS_SUCCESS)
      status = cairo_surface_status(surface);
  }
  cairo_surface_destroy(surface);
  return file.commit(status, error);
}

}  // namespace maps
}  // namespace pcl_ls3d
