#pragma once
// `owsim studio` (INTERFACE.md "Studio", docs/studio.md): a cpp-httplib server on the loopback
// address serving the web app (web/studio/, bundled at build time) and a small JSON API over the
// facade — the scenario's YAML, what the loader makes of an edit (the map's view, or the loader's
// one-line error with its line and key), Save, Fly (one run at a time, progress, cancel) and the
// output folder's files (the report page). Every request passes request_guard.hpp and
// request_path.hpp, every connection bounded_http_server.hpp's bounds, every body at most 8 MB
// however it is sent; files are read only inside the scenario's folder tree and the output
// folder, and written only to the scenario file and the output folder.
#include <filesystem>
#include <memory>
#include <string>

namespace owsim::studio {

struct StudioOptions {
  std::filesystem::path scenario_file;  // read when it exists, written by Save
  std::string initial_yaml;             // the scenario's text when the file does not exist yet
  std::filesystem::path out;            // the output folder of Fly
  int port = 0;                         // 0: a free port
  std::string token;                    // empty: a new random one
};

class StudioServer {
 public:
  // Binds 127.0.0.1 (only); throws owsim::Error when the port cannot be bound, or when the
  // output folder cannot be Fly's (flight_job.hpp check_output_folder).
  explicit StudioServer(StudioOptions options);
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;
  ~StudioServer();

  [[nodiscard]] int port() const;
  [[nodiscard]] const std::string& token() const;
  // http://127.0.0.1:PORT/?token=TOKEN
  [[nodiscard]] std::string address() const;
  // Serves until stop() (from another thread or a signal handler's thread).
  void serve();
  // Stops serving and cancels a run in progress (waits for it to remove its partial files).
  void stop();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace owsim::studio
