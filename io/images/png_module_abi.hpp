#pragma once
// The C entry points of libowsim_png.so (io/images/oiio/png_module.cpp), the optional module
// that encodes PNG images with OpenImageIO. The loader (io/images/png_image.cpp) refuses a module
// whose owsim_png_module_abi() differs from OWSIM_PNG_MODULE_ABI.
#include <cstddef>

#define OWSIM_PNG_MODULE_ABI 1

extern "C" {

// Receives the encoded PNG bytes (called once, before owsim_png_encode returns 0).
typedef void (*owsim_png_sink)(void* context, const unsigned char* data, std::size_t size);

typedef int (*owsim_png_module_abi_fn)(void);
// Encodes width × height 8-bit RGB pixels (row-major, top row first) as PNG. Returns 0 and calls
// `sink` once, or returns non-zero with a one-line message in `error`.
typedef int (*owsim_png_encode_fn)(const unsigned char* rgb, int width, int height,
                                   owsim_png_sink sink, void* sink_context, char* error,
                                   std::size_t error_size);
}
