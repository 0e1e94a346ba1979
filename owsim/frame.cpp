#include "owsim/frame.hpp"

#include <bit>

#include "io/points/frame_points.hpp"
#include "io/recording/frame_words.hpp"

namespace owsim {

static_assert(std::endian::native == std::endian::little,
              "Frame::word_bytes hands out the words as the files hold them: little-endian");

std::span<const std::byte> Frame::word_bytes() const {
  if (model_ == SensorModel::hellas) return std::as_bytes(std::span(hellas_words_));
  return std::as_bytes(std::span(milows_words_));
}

void Frame::encode(const ScanParams& scan, const LocalFrame& local_frame) {
  model_ = scan.model;
  const std::size_t pulses = result_.pulses.size();
  if (model_ == SensorModel::hellas) {
    milows_words_.clear();
    hellas_words_.resize(pulses);
    pack_hellas_frame(scan, result_.sweep, result_.pulses, result_.returns, hellas_words_);
  } else {
    hellas_words_.clear();
    milows_words_.resize(pulses);
    pack_milows_frame(result_.pulses, result_.returns, milows_words_);
  }

  frame_points(result_.view(), local_frame, points_);
  returns_.resize(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const PointRecord& point = points_[i];
    ReturnRecord& record = returns_[i];
    record.frame = point.frame;
    record.pulse = point.pulse;
    record.line = point.line;
    record.fiber = point.fiber;
    record.return_number = point.return_number;
    record.time_s = point.time_s;
    record.range_m = point.range_m;
    record.counter = point.counter;
    record.surface = point.surface ? static_cast<std::uint8_t>(*point.surface) : kUnknownSurface;
    record.number_of_returns = static_cast<std::uint8_t>(point.number_of_returns);
    record.object = point.object_index;
    record.e_m = point.enu_m.x();
    record.n_m = point.enu_m.y();
    record.u_m = point.enu_m.z();
    record.lat_deg = point.geodetic.lat_deg;
    record.lon_deg = point.geodetic.lon_deg;
    record.h_m = point.geodetic.h_m;
    record.energy_rel = point.energy_rel;
    record.incidence_deg = point.incidence_deg;
  }
}

}  // namespace owsim
