// libowsim_png.so: the one place owsim touches OpenImageIO. Loaded on demand by
// io/images/png_image.cpp when a run writes quick-look images, so that the owsim executable,
// libowsim_c.so and the Python module need neither OpenImageIO nor the library tree behind it
// (OpenCV, ffmpeg, GDAL, …). The entry points are plain C: no exception crosses them.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "io/images/png_module_abi.hpp"

namespace {

void copy_error(const std::string& message, char* error, std::size_t error_size) {
  if (error == nullptr || error_size == 0) return;
  std::snprintf(error, error_size, "%s", message.c_str());
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int owsim_png_module_abi(void) {
  return OWSIM_PNG_MODULE_ABI;
}

extern "C" __attribute__((visibility("default"))) int owsim_png_encode(
    const unsigned char* rgb, int width, int height, owsim_png_sink sink, void* sink_context,
    char* error, std::size_t error_size) {
  try {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto output = OIIO::ImageOutput::create("png", &proxy);
    if (!output) {
      copy_error("OpenImageIO has no PNG writer: " + OIIO::geterror(), error, error_size);
      return 1;
    }
    const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (!output->open("memory.png", spec) || !output->write_image(OIIO::TypeDesc::UINT8, rgb) ||
        !output->close()) {
      copy_error("cannot encode the image: " + output->geterror(), error, error_size);
      return 1;
    }
    sink(sink_context, bytes.data(), bytes.size());
    return 0;
  } catch (const std::exception& e) {
    copy_error(e.what(), error, error_size);
  } catch (...) {
    copy_error("unknown error", error, error_size);
  }
  return 1;
}
