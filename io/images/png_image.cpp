#include "io/images/png_image.hpp"

#include <array>
#include <string>

#include "geometry/error.hpp"
#include "io/files/optional_module.hpp"
#include "io/images/png_module_abi.hpp"

namespace owsim {
namespace {

constexpr std::string_view kPngPurpose = "quick-look images";

// The PNG encoder of the optional module libowsim_png.so (OpenImageIO), loaded on first use.
owsim_png_encode_fn png_encoder() {
  static const owsim_png_encode_fn encode = [] {
    const auto& module = OptionalModule::get("png", kPngPurpose, OWSIM_PNG_MODULE_ABI);
    return reinterpret_cast<owsim_png_encode_fn>(module.symbol("owsim_png_encode"));
  }();
  return encode;
}

constexpr int kMaxImageSidePx = 65'536;

// ColorBrewer "Blues" (9 classes), light → dark, at t = 0, 1/8, …, 1.
constexpr std::array<Rgb8, 9> kBluesRamp = {{{247, 251, 255},
                                             {222, 235, 247},
                                             {198, 219, 239},
                                             {158, 202, 225},
                                             {107, 174, 214},
                                             {66, 146, 198},
                                             {33, 113, 181},
                                             {8, 81, 156},
                                             {8, 48, 107}}};

std::uint8_t mix(std::uint8_t a, std::uint8_t b, double w) {
  return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * w));
}

}  // namespace

RgbImage::RgbImage(int width, int height, Rgb8 fill_colour) : width_(width), height_(height) {
  if (width < 1 || height < 1 || width > kMaxImageSidePx || height > kMaxImageSidePx) {
    throw Error("image: size " + std::to_string(width) + " x " + std::to_string(height) +
                " outside 1..65536 pixels a side");
  }
  bytes_.resize(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  fill(fill_colour);
}

void RgbImage::fill(Rgb8 colour) {
  for (std::size_t i = 0; i < bytes_.size(); i += 3) {
    bytes_[i] = colour.r;
    bytes_[i + 1] = colour.g;
    bytes_[i + 2] = colour.b;
  }
}

void draw_line(RgbImage& image, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
               Rgb8 colour) {
  for_each_line_pixel(from, to, image.width(), image.height(),
                      [&](int x, int y) { image.set(x, y, colour); });
}

void fill_circle(RgbImage& image, int cx, int cy, int radius_px, Rgb8 colour) {
  const int r = std::max(radius_px, 0);
  const long long r2 = static_cast<long long>(r) * r;
  const int y_first = std::max(cy - r, 0), y_last = std::min(cy + r, image.height() - 1);
  const int x_first = std::max(cx - r, 0), x_last = std::min(cx + r, image.width() - 1);
  for (int y = y_first; y <= y_last; ++y) {
    for (int x = x_first; x <= x_last; ++x) {
      const long long dx = x - cx, dy = y - cy;
      if (dx * dx + dy * dy <= r2) image.set(x, y, colour);
    }
  }
}

RgbImage enlarged(const RgbImage& image, int factor) {
  if (factor < 1) throw Error("image: enlargement factor " + std::to_string(factor) + " < 1");
  RgbImage out(image.width() * factor, image.height() * factor);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) out.set(x, y, image.at(x / factor, y / factor));
  }
  return out;
}

Rgb8 range_ramp_colour(double t) {
  const double s = std::isnan(t) ? 1.0 : std::clamp(t, 0.0, 1.0);
  const double position = s * static_cast<double>(kBluesRamp.size() - 1);
  const auto lower = std::min(static_cast<std::size_t>(position), kBluesRamp.size() - 2);
  const double w = position - static_cast<double>(lower);
  const Rgb8 a = kBluesRamp[lower], b = kBluesRamp[lower + 1];
  return {mix(a.r, b.r, w), mix(a.g, b.g, w), mix(a.b, b.b, w)};
}

void require_png_encoder() { static_cast<void>(png_encoder()); }

std::vector<unsigned char> encode_png(const RgbImage& image) {
  std::vector<unsigned char> bytes;
  std::array<char, 512> error{};
  const owsim_png_sink append = [](void* context, const unsigned char* data, std::size_t size) {
    auto& out = *static_cast<std::vector<unsigned char>*>(context);
    out.insert(out.end(), data, data + size);
  };
  if (png_encoder()(image.bytes().data(), image.width(), image.height(), append, &bytes,
                    error.data(), error.size()) != 0) {
    throw Error(std::string("png: ") + error.data());
  }
  return bytes;
}

void write_png(const std::filesystem::path& path, const RgbImage& image,
               AtomicOutputOptions options) {
  std::vector<unsigned char> bytes;
  try {
    bytes = encode_png(image);
  } catch (const Error& e) {
    throw input_error(path.string(), e.what());
  }
  AtomicOutputFile file(path, options);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

}  // namespace owsim
