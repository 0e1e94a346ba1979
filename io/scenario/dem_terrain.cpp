#include "io/scenario/dem_terrain.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "geometry/error.hpp"
#include "io/scenario/gdal_module.hpp"
#include "io/scenario/gdal_module_abi.hpp"

namespace owsim {
namespace {

// What the module hands back, placed in the local frame.
struct LatticeSink {
  const LocalFrame* frame;
  bool whole_file;
  PostLattice lattice;
  std::string refusal;  // why begin refused the lattice's size
};

std::string gigabytes(double bytes) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(bytes < 1e10 ? 1 : 0) << bytes / 1e9 << " GB";
  return text.str();
}

int begin_posts(void* context, int ncols, int nrows) {
  auto* sink = static_cast<LatticeSink*>(context);
  const auto count = static_cast<std::size_t>(ncols) * static_cast<std::size_t>(nrows);
  const double needed = static_cast<double>(count) * kDemBytesPerPost;
  const double memory =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (count > std::numeric_limits<std::uint32_t>::max() || needed > memory) {
    sink->refusal = std::string(sink->whole_file ? "the DEM"
                                                 : "the part of the DEM in the "
                                                   "flight's reach") +
                    " is " + std::to_string(ncols) + " × " + std::to_string(nrows) +
                    " posts, about " + gigabytes(needed) + " at " +
                    std::to_string(kDemBytesPerPost) + " bytes a post, more than this machine's " +
                    gigabytes(memory) +
                    " of memory: resample it coarser (gdalwarp -tr) or cut it to the flight's "
                    "area (gdal_translate -projwin)";
    return 1;
  }
  PostLattice& lattice = sink->lattice;
  lattice.ncols = ncols;
  lattice.nrows = nrows;
  lattice.posts.resize(count);
  lattice.valid.resize(count);
  return 0;
}

void receive_rows(void* context, int row0, int nrows, const double* lon_lat_h,
                  const unsigned char* valid) {
  auto* sink = static_cast<LatticeSink*>(context);
  PostLattice& lattice = sink->lattice;
  const std::size_t first = lattice.index(row0, 0);
  const auto count = static_cast<std::size_t>(lattice.ncols) * static_cast<std::size_t>(nrows);
  std::copy(valid, valid + count, lattice.valid.begin() + static_cast<std::ptrdiff_t>(first));
  for (std::size_t i = 0; i < count; ++i) {
    const Geodetic post{lon_lat_h[3 * i + 1], lon_lat_h[3 * i], lon_lat_h[3 * i + 2]};
    lattice.posts[first + i] = sink->frame->enu_from_geodetic(post);
  }
}

// The WGS-84 box around an east/north box of the local frame: its edges sampled (they are
// curves in latitude and longitude), at the origin's height.
std::array<double, 4> geodetic_box(const Eigen::AlignedBox2d& reach, const LocalFrame& frame) {
  constexpr int kSamples = 16;
  double lon_min = 1e9, lat_min = 1e9, lon_max = -1e9, lat_max = -1e9;
  for (int i = 0; i <= kSamples; ++i) {
    const double s = static_cast<double>(i) / kSamples;
    const Eigen::Vector2d lo = reach.min(), hi = reach.max();
    for (const Eigen::Vector2d& en : {Eigen::Vector2d(lo.x() + s * (hi.x() - lo.x()), lo.y()),
                                      Eigen::Vector2d(lo.x() + s * (hi.x() - lo.x()), hi.y()),
                                      Eigen::Vector2d(lo.x(), lo.y() + s * (hi.y() - lo.y())),
                                      Eigen::Vector2d(hi.x(), lo.y() + s * (hi.y() - lo.y()))}) {
      const Geodetic point = frame.geodetic_from_enu(Eigen::Vector3d(en.x(), en.y(), 0.0));
      lon_min = std::min(lon_min, point.lon_deg);
      lon_max = std::max(lon_max, point.lon_deg);
      lat_min = std::min(lat_min, point.lat_deg);
      lat_max = std::max(lat_max, point.lat_deg);
    }
  }
  return {lon_min, lat_min, lon_max, lat_max};
}

}  // namespace

PostLattice read_dem_terrain(const std::filesystem::path& file, const LocalFrame& frame,
                             const std::optional<Eigen::AlignedBox2d>& reach) {
  const auto read = reinterpret_cast<owsim_dem_read_fn>(
      gdal_module("DEM terrain (terrain.dem)").symbol("owsim_dem_read"));
  const std::array<double, 4> box =
      reach ? geodetic_box(*reach, frame) : std::array<double, 4>{0.0, 0.0, 0.0, 0.0};
  LatticeSink sink{&frame, !reach, {}, {}};
  std::array<char, 1024> error{};
  if (read(file.c_str(), reach ? 0 : 1, box[0], box[1], box[2], box[3], begin_posts, receive_rows,
           &sink, error.data(), error.size()) != 0) {
    throw Error(file.string() + ": " + (sink.refusal.empty() ? error.data() : sink.refusal));
  }
  sink.lattice.validate(file.string());
  return std::move(sink.lattice);
}

}  // namespace owsim
