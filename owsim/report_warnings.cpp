#include "owsim/report_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "evaluation/detections_csv.hpp"

namespace owsim {

nlohmann::json report_warnings_json(const std::filesystem::path& detections_csv,
                                    const Scenario& scenario, std::int64_t frames,
                                    std::size_t max_tracks) {
  struct Track {
    std::string id, kind;
    double e = 0, n = 0, u = 0;
    std::int64_t first = 0, last = 0;
  };
  const double period = scenario.scan.frame_duration_s();
  const LocalFrame frame(scenario.origin);
  const DetectionFlight flight{frame, scenario.scan.start_s,
                               scenario.scan.start_s + static_cast<double>(frames) * period};
  std::vector<Track> tracks;
  std::map<std::string, std::size_t> index_of;
  read_detections_csv(detections_csv, flight, [&](const Detection& d) {
    const auto at = std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::floor((d.time_s - flight.start_s) / period + 1e-6)), 0,
        std::max<std::int64_t>(frames - 1, 0));
    std::size_t t = tracks.size();
    if (!d.track.empty()) {
      const auto [found, added] = index_of.emplace(d.track, tracks.size());
      t = found->second;
      if (!added) {
        Track& track = tracks[t];
        track.kind = d.object_class;
        track.e = d.enu_m.x();
        track.n = d.enu_m.y();
        track.u = d.enu_m.z();
        track.first = std::min(track.first, at);
        track.last = std::max(track.last, at);
        return;
      }
    }
    tracks.push_back({d.track, d.object_class, d.enu_m.x(), d.enu_m.y(), d.enu_m.z(), at, at});
  });
  std::stable_sort(tracks.begin(), tracks.end(),
                   [](const Track& a, const Track& b) { return a.first < b.first; });
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t t = 0; t < tracks.size() && t < max_tracks; ++t) {
    const Track& track = tracks[t];
    const auto cm = [](double v) { return std::round(v * 100.0) / 100.0; };
    out.push_back({{"track", track.id},
                   {"class", track.kind},
                   {"e_m", cm(track.e)},
                   {"n_m", cm(track.n)},
                   {"u_m", cm(track.u)},
                   {"first_frame", track.first},
                   {"last_frame", track.last}});
  }
  return {{"tracks", std::move(out)}, {"tracks_total", tracks.size()}};
}

}  // namespace owsim
