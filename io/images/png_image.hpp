#pragma once
// A small 8-bit RGB raster for the quick-look images (INTERFACE.md "`owsim run` outputs",
// quicklook/): set a pixel, draw a clipped line, fill a circle, enlarge by an integer factor, and
// write the result as an 8-bit RGB PNG. The PNG is encoded in memory by OpenImageIO (in the
// optional module libowsim_png.so, loaded on first use) and written
// through AtomicOutputFile, so nothing half-written appears under the final name.
//
// Pixel (x, y): x = column from the left, y = row from the top; pixel centres sit at integer
// coordinates, so a continuous point (x, y) falls in pixel (round(x), round(y)). Drawing outside
// the raster is clipped silently. The range ramp is a sequential blue ramp (ColorBrewer "Blues"
// control points, interpolated linearly in sRGB): near returns light, far ones dark navy — it
// holds no red, orange or green, so class colours stay unambiguous next to it.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "io/files/atomic_output_file.hpp"

namespace owsim {

struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

class RgbImage {
 public:
  // Throws owsim::Error unless 1 ≤ width, height ≤ 65,536.
  RgbImage(int width, int height, Rgb8 fill = {});

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] bool contains(int x, int y) const {
    return x >= 0 && y >= 0 && x < width_ && y < height_;
  }
  // The pixel's colour; (x, y) must lie inside.
  [[nodiscard]] Rgb8 at(int x, int y) const {
    const std::size_t i = offset(x, y);
    return {bytes_[i], bytes_[i + 1], bytes_[i + 2]};
  }
  // Sets one pixel; a pixel outside the raster is ignored.
  void set(int x, int y, Rgb8 colour) {
    if (!contains(x, y)) return;
    const std::size_t i = offset(x, y);
    bytes_[i] = colour.r;
    bytes_[i + 1] = colour.g;
    bytes_[i + 2] = colour.b;
  }
  void fill(Rgb8 colour);
  // Row-major RGB bytes, top row first, 3 per pixel.
  [[nodiscard]] std::span<const std::uint8_t> bytes() const { return bytes_; }

 private:
  [[nodiscard]] std::size_t offset(int x, int y) const {
    return 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                static_cast<std::size_t>(x));
  }

  int width_;
  int height_;
  std::vector<std::uint8_t> bytes_;
};

// Calls plot(x, y) for every pixel of the segment from→to (continuous pixel coordinates) that
// lies inside a width × height raster: Bresenham's walk between the rounded end points, one pixel
// per step along the longer axis. The segment is first clipped to the raster grown by half a
// pixel, so a segment kilometres long costs no more than the raster's size.
template <class Plot>
void for_each_line_pixel(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int width,
                         int height, Plot&& plot) {
  // Liang–Barsky clip to [−1, width] × [−1, height].
  const Eigen::Vector2d d = to - from;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {from.x() + 1.0, width - from.x(), from.y() + 1.0, height - from.y()};
  for (int k = 0; k < 4; ++k) {
    if (!std::isfinite(p[k]) || !std::isfinite(q[k])) return;
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return;
    } else if (p[k] < 0.0) {
      t0 = std::max(t0, q[k] / p[k]);
    } else {
      t1 = std::min(t1, q[k] / p[k]);
    }
  }
  if (t0 > t1) return;
  const Eigen::Vector2d a = from + t0 * d, b = from + t1 * d;
  int x = static_cast<int>(std::lround(a.x())), y = static_cast<int>(std::lround(a.y()));
  const int x_end = static_cast<int>(std::lround(b.x())),
            y_end = static_cast<int>(std::lround(b.y()));
  const int dx = std::abs(x_end - x), dy = -std::abs(y_end - y);
  const int step_x = x < x_end ? 1 : -1, step_y = y < y_end ? 1 : -1;
  int error = dx + dy;
  while (true) {
    if (x >= 0 && y >= 0 && x < width && y < height) plot(x, y);
    if (x == x_end && y == y_end) break;
    const int twice = 2 * error;
    if (twice >= dy) {
      error += dy;
      x += step_x;
    }
    if (twice <= dx) {
      error += dx;
      y += step_y;
    }
  }
}

// A one-pixel line from→to (continuous pixel coordinates), clipped to the image.
void draw_line(RgbImage& image, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
               Rgb8 colour);
// Every pixel whose centre lies within radius_px of (cx, cy); radius 0 is the one pixel.
void fill_circle(RgbImage& image, int cx, int cy, int radius_px, Rgb8 colour);
// Each pixel becomes a factor × factor block (nearest neighbour). Throws for factor < 1.
[[nodiscard]] RgbImage enlarged(const RgbImage& image, int factor);

// The range ramp at t = range / full scale, clamped to [0, 1]: t = 0 light (247, 251, 255),
// t = 1 dark navy (8, 48, 107); NaN gives the far end.
[[nodiscard]] Rgb8 range_ramp_colour(double t);

// Loads the PNG encoder (the optional module libowsim_png.so, OpenImageIO; see
// io/files/optional_module.hpp) unless it is loaded; throws owsim::Error saying why it cannot be.
// A run that will write images calls it before it writes anything.
void require_png_encoder();
// The image as PNG bytes (8-bit RGB), encoded in memory by OpenImageIO in libowsim_png.so.
// Throws owsim::Error with OIIO's message on failure.
[[nodiscard]] std::vector<unsigned char> encode_png(const RgbImage& image);
// encode_png written to `<path>.partial` and renamed to `path` (AtomicOutputFile). Throws
// owsim::Error naming the path.
void write_png(const std::filesystem::path& path, const RgbImage& image,
               AtomicOutputOptions options = {});

}  // namespace owsim
