#include "studio/studio_server.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/confined_path.hpp"
#include "io/files/input_file.hpp"
#include "owsim/simulation.hpp"
#include "studio/flight_job.hpp"
#include "studio/loader_message.hpp"
#include "studio/request_guard.hpp"
#include "studio/scene_view.hpp"
#include "studio/studio_page.hpp"

// After every header that includes Eigen: httplib.h includes <resolv.h>, whose `_res` macro
// would rewrite Eigen's parameters of that name.
#include <httplib.h>

namespace owsim::studio {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::size_t kMaxRequestBytes = 8u << 20;  // a scenario's YAML is kilobytes

// Everything the browser may load or call from the app: its own origin and nothing else, so no
// request leaves the machine even if a script tried.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data: blob:; connect-src 'self'; frame-src 'self'; object-src 'none'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'self'";
// The report page inlines its script and data: the same origin rule, inline allowed.
constexpr const char* kReportSecurityPolicy =
    "default-src 'self' 'unsafe-inline' data: blob:; connect-src 'self'; object-src 'none'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'self'";

std::optional<std::string> header(const httplib::Request& request, const char* name) {
  if (!request.has_header(name)) return std::nullopt;
  return request.get_header_value(name);
}

void send_json(httplib::Response& response, const json& body, int status = 200) {
  response.status = status;
  response.set_content(body.dump(), "application/json");
}

std::string_view content_type_of(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".json") return "application/json";
  if (extension == ".csv" || extension == ".yaml" || extension == ".txt") {
    return "text/plain; charset=utf-8";
  }
  if (extension == ".png") return "image/png";
  if (extension == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

}  // namespace

struct StudioServer::State {
  StudioOptions options;
  std::filesystem::path folder;  // the scenario's folder (canonical)
  httplib::Server server;
  int port = 0;
  std::mutex save_mutex;
  FlightJob job;

  // The loader's verdict on `yaml`: the Simulation it builds, or the error as JSON.
  std::variant<Simulation, json> load(const std::string& yaml) const {
    try {
      return Simulation::from_yaml(yaml, options.scenario_file);
    } catch (const std::exception& error) {
      return loader_message(error.what(), options.scenario_file.string());
    }
  }

  void routes();
};

void StudioServer::State::routes() {
  server.Get("/", [this](const httplib::Request&, httplib::Response& response) {
    // The token in the address becomes a cookie the app's own requests carry.
    response.set_header("Set-Cookie", std::string(kTokenCookie) + "=" + options.token +
                                          "; Path=/; HttpOnly; SameSite=Strict");
    response.set_header("Content-Security-Policy", kContentSecurityPolicy);
    response.set_content(std::string(studio_page_html()), "text/html; charset=utf-8");
  });
  server.Get("/studio.js", [](const httplib::Request&, httplib::Response& response) {
    response.set_content(std::string(studio_script()), "text/javascript; charset=utf-8");
  });
  server.Get("/api/session", [this](const httplib::Request&, httplib::Response& response) {
    std::string yaml = options.initial_yaml;
    std::error_code error;
    if (std::filesystem::is_regular_file(options.scenario_file, error)) {
      yaml = read_input_file(options.scenario_file, "scenario file", kMaxScenarioBytes);
    }
    send_json(response, {{"scenario", options.scenario_file.filename().string()},
                         {"folder", folder.string()},
                         {"out", options.out.string()},
                         {"yaml", yaml},
                         {"run", job.status()}});
  });
  server.Post("/api/view", [this](const httplib::Request& request, httplib::Response& response) {
    auto loaded = load(request.body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    send_json(response, {{"ok", true}, {"view", scene_view(std::get<Simulation>(loaded))}});
  });
  // WGS-84 points as east/north metres in the local frame of `origin` (a rectangle drawn on the
  // map becomes a forest's area or a fog box, keys that take metres).
  server.Post("/api/enu", [](const httplib::Request& request, httplib::Response& response) {
    try {
      const json body = json::parse(request.body);
      const json& origin = body.at("origin");
      const LocalFrame frame(Geodetic{origin.at("lat").get<double>(),
                                      origin.at("lon").get<double>(),
                                      origin.at("h").get<double>()});
      json points = json::array();
      for (const json& point : body.at("points")) {
        const Eigen::Vector3d enu = frame.enu_from_geodetic(
            {point.at(0).get<double>(), point.at(1).get<double>(), origin.at("h").get<double>()});
        points.push_back({enu.x(), enu.y()});
      }
      send_json(response, {{"ok", true}, {"points", points}});
    } catch (const std::exception& error) {
      send_json(response,
                {{"ok", false}, {"problem", {{"message", std::string("studio: ") + error.what()}}}},
                400);
    }
  });
  server.Post("/api/save", [this](const httplib::Request& request, httplib::Response& response) {
    auto loaded = load(request.body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    const std::lock_guard lock(save_mutex);
    AtomicOutputFile file(options.scenario_file);
    file.write(request.body);
    file.commit();
    send_json(response, {{"ok", true}, {"saved", options.scenario_file.filename().string()}});
  });
  server.Post("/api/fly", [this](const httplib::Request& request, httplib::Response& response) {
    auto loaded = load(request.body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    std::filesystem::create_directories(options.out);
    if (!job.start(request.body, options.scenario_file, options.out)) {
      send_json(response, {{"ok", false}, {"problem", {{"message", "a run is in progress"}}}}, 409);
      return;
    }
    send_json(response, {{"ok", true}, {"run", job.status()}});
  });
  // The model files in the scenario's folder tree (what a mesh's `file` may name), relative,
  // sorted; the output folder and hidden folders are not searched, and links are not followed.
  server.Get("/api/models", [this](const httplib::Request&, httplib::Response& response) {
    json files = json::array();
    std::error_code error;
    const fs::path out = fs::weakly_canonical(options.out, error);
    for (auto entry = fs::recursive_directory_iterator(folder, error);
         !error && entry != fs::recursive_directory_iterator(); entry.increment(error)) {
      const std::string name = entry->path().filename().string();
      if (entry->is_directory(error) &&
          (name.starts_with(".") || entry->path() == out || entry.depth() >= 3)) {
        entry.disable_recursion_pending();
        continue;
      }
      if (!entry->is_regular_file(error) || entry->is_symlink(error)) continue;
      std::string extension = entry->path().extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension == ".obj" || extension == ".ply" || extension == ".stl" ||
          extension == ".off" || extension == ".gltf" || extension == ".glb") {
        files.push_back(entry->path().lexically_relative(folder).generic_string());
      }
      if (files.size() >= 1000) break;
    }
    std::sort(files.begin(), files.end());
    send_json(response, {{"ok", true}, {"files", files}});
  });
  server.Get("/api/run", [this](const httplib::Request&, httplib::Response& response) {
    send_json(response, job.status());
  });
  server.Post("/api/cancel", [this](const httplib::Request&, httplib::Response& response) {
    job.cancel();
    send_json(response, job.status());
  });
  // The output folder's files (the report page and what it links), confined to the folder.
  server.Get(R"(/out/(.+))", [this](const httplib::Request& request, httplib::Response& response) {
    try {
      const std::filesystem::path root = std::filesystem::weakly_canonical(options.out);
      const std::filesystem::path file = confined_file(root, request.matches[1].str());
      response.set_header("Content-Security-Policy", kReportSecurityPolicy);
      response.set_content(read_input_file(file, "output file", 0),
                           std::string(content_type_of(file)));
    } catch (const std::exception& error) {
      send_json(response, {{"ok", false}, {"problem", {{"message", error.what()}}}}, 404);
    }
  });
}

StudioServer::StudioServer(StudioOptions options) : state_(std::make_unique<State>()) {
  State& state = *state_;
  if (options.token.empty()) options.token = new_session_token();
  options.scenario_file = std::filesystem::absolute(options.scenario_file);
  options.out = std::filesystem::absolute(options.out);
  state.folder = std::filesystem::weakly_canonical(options.scenario_file.parent_path());
  state.options = std::move(options);
  httplib::Server& server = state.server;
  server.set_payload_max_length(kMaxRequestBytes);
  server.set_pre_routing_handler(
      [&state](const httplib::Request& request, httplib::Response& response) {
        RequestFacts facts;
        facts.host = header(request, "Host");
        facts.origin = header(request, "Origin");
        facts.token_header = header(request, "X-Owsim-Token");
        facts.cookie = header(request, "Cookie");
        if (request.has_param("token")) facts.token_query = request.get_param_value("token");
        const Verdict verdict = check_request(facts, state.port, state.options.token);
        if (verdict == Verdict::allowed) return httplib::Server::HandlerResponse::Unhandled;
        response.status = verdict == Verdict::no_token ? 401 : 403;
        response.set_content(std::string(verdict_text(verdict)) + "\n", "text/plain");
        return httplib::Server::HandlerResponse::Handled;
      });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
        std::string message = "studio: an unexpected error";
        try {
          std::rethrow_exception(std::move(error));
        } catch (const std::exception& exception) {
          message = exception.what();
        } catch (...) {
        }
        send_json(response, {{"ok", false}, {"problem", {{"message", message}}}}, 500);
      });
  state.routes();
  const std::string loopback = "127.0.0.1";
  if (state.options.port == 0) {
    state.port = server.bind_to_any_port(loopback);
  } else {
    state.port = server.bind_to_port(loopback, state.options.port) ? state.options.port : -1;
  }
  if (state.port <= 0) {
    throw Error("studio: cannot listen on " + loopback + ":" + std::to_string(state.options.port) +
                " (in use?)");
  }
}

StudioServer::~StudioServer() { stop(); }

int StudioServer::port() const { return state_->port; }
const std::string& StudioServer::token() const { return state_->options.token; }
std::string StudioServer::address() const {
  return "http://127.0.0.1:" + std::to_string(state_->port) + "/?token=" + state_->options.token;
}

void StudioServer::serve() { state_->server.listen_after_bind(); }

void StudioServer::stop() {
  state_->job.cancel();
  state_->job.wait();
  state_->server.stop();
}

}  // namespace owsim::studio
