#include "owsim/frame.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
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

namespace {

constexpr std::size_t kEncodeGrain = 1024;  // pulses per task

ReturnRecord return_record(const PointRecord& point) {
  ReturnRecord record;
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
  return record;
}

}  // namespace

void Frame::encode(const ScanParams& scan, const GeodesyCells& geodesy) {
  model_ = scan.model;
  const FrameView view = result_.view();
  const std::size_t pulses = result_.pulses.size();
  if (model_ == SensorModel::hellas) {
    milows_words_.clear();
    hellas_words_.resize(pulses);
  } else {
    hellas_words_.clear();
    milows_words_.resize(pulses);
  }
  // The returns the sensor records: HELLAS's words hold the first alone (SENSOR-SPEC §8).
  const int recorded = recorded_returns(model_);
  first_return_.resize(pulses + 1);
  first_return_[0] = 0;
  for (std::size_t k = 0; k < pulses; ++k) {
    first_return_[k + 1] =
        first_return_[k] + static_cast<std::size_t>(std::min(result_.returns[k].count, recorded));
  }
  returns_.resize(first_return_[pulses]);

  const std::span<const Pulse> all_pulses(result_.pulses);
  const std::span<const PulseReturns> all_returns(result_.returns);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pulses, kEncodeGrain), [&](const auto& r) {
    const std::size_t n = r.size();
    if (model_ == SensorModel::hellas) {
      pack_hellas_frame(scan, result_.sweep, all_pulses.subspan(r.begin(), n),
                        all_returns.subspan(r.begin(), n),
                        std::span(hellas_words_).subspan(r.begin(), n));
    } else {
      pack_milows_frame(all_pulses.subspan(r.begin(), n), all_returns.subspan(r.begin(), n),
                        std::span(milows_words_).subspan(r.begin(), n));
    }
    GeodesyCells::Cursor cursor;
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const int count = std::min(result_.returns[k].count, recorded);
      for (int i = 0; i < count; ++i) {
        returns_[first_return_[k] + static_cast<std::size_t>(i)] =
            return_record(point_record(view, k, i, geodesy, cursor, recorded));
      }
    }
  });
}

}  // namespace owsim
