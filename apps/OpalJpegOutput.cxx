// The JPEG output module of opal-render (OpalOutputModules.h): 8-bit sRGB
// through libjpeg with an error handler that returns to the caller. Through
// OpenImageIO, libjpeg kept its default handler, which calls exit() on any
// error, a full disk among them: the run ended with its earlier outputs
// replaced and its temporary files left behind.
#include "OpalAtomicFile.h"
#include "OpalOutputModules.h"

#include <csetjmp>
#include <cstdio>

#include <jpeglib.h>

namespace
{
// libjpeg's state for one image and the way back from its errors.
struct Compression
{
  jpeg_compress_struct Info{};
  jpeg_error_mgr Errors{};
  std::jmp_buf Return{};
  char Message[JMSG_LENGTH_MAX] = "";
};

// libjpeg's error_exit: keeps the message and returns to compress(), which
// destroys the state; libjpeg expects this handler not to return.
[[noreturn]] void returnFromError(j_common_ptr info)
{
  auto* compression = static_cast<Compression*>(info->client_data);
  compression->Errors.format_message(info, compression->Message);
  std::longjmp(compression->Return, 1);
}

// Compresses the image into `file`; false with libjpeg's message in
// `compression`. Everything libjpeg touches lives in `compression`, outside
// this frame, and nothing here has a destructor for longjmp to skip.
bool compress(Compression& compression, std::FILE* file, const opal::RenderImage& image)
{
  jpeg_compress_struct& info = compression.Info;
  info.err = jpeg_std_error(&compression.Errors);
  compression.Errors.error_exit = &returnFromError;
  info.client_data = &compression;
  if (setjmp(compression.Return) != 0)
  {
    jpeg_destroy_compress(&info);
    return false;
  }
  jpeg_create_compress(&info); // keeps err and client_data
  jpeg_stdio_dest(&info, file);
  info.image_width = static_cast<JDIMENSION>(image.Region[2]);
  info.image_height = static_cast<JDIMENSION>(image.Region[3]);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 98, TRUE); // OpenImageIO's default, which wrote these files before
  jpeg_start_compress(&info, TRUE);
  const std::size_t rowBytes = 3 * static_cast<std::size_t>(info.image_width);
  while (info.next_scanline < info.image_height)
  {
    // libjpeg takes rows as non-const but only reads them.
    JSAMPROW row = const_cast<JSAMPROW>(image.RGB.data() + info.next_scanline * rowBytes);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return true;
}

// Writes the image's 8-bit sRGB pixels (rows top to bottom) as a JPEG;
// false with the reason.
bool writeJpeg(const std::string& path, const opal::RenderImage& image, std::string& reason)
{
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file)
  {
    reason = "cannot open the file";
    return false;
  }
  Compression compression;
  const bool compressed = compress(compression, file, image);
  const bool closed = std::fclose(file) == 0; // flushes: a full disk may show only here
  reason = compressed ? "" : compression.Message;
  return compressed && closed;
}

std::string writeImage(const opal::RenderImage& image, const std::string& path, bool /*spectralChannels*/)
{
  return writeFileAtomically(
    path, [&](const std::string& file, std::string& reason) { return writeJpeg(file, image, reason); });
}

const opal::ImageOutputModule module{ &writeImage };
} // namespace

const opal::ImageOutputModule* opalJpegOutputModule()
{
  return &module;
}
