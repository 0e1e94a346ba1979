#include "studio/studio_server.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/input_file.hpp"
#include "owsim/simulation.hpp"
#include "studio/flight_job.hpp"
#include "studio/loader_message.hpp"
#include "studio/request_guard.hpp"
#include "studio/request_path.hpp"
#include "studio/scene_view.hpp"
#include "studio/studio_page.hpp"

// After every header that includes Eigen: httplib.h includes <resolv.h>, whose `_res` macro
// would rewrite Eigen's parameters of that name.
#include <httplib.h>

#include "studio/bounded_http_server.hpp"
#include "studio/served_file.hpp"

namespace owsim::studio {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Every request body, however it comes (a length, chunks, gzip), as the route reads it.
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

// Text that is not UTF-8 (a file name on disk, bytes of a request) goes out as U+FFFD, never as
// an exception from the JSON library.
void send_json(httplib::Response& response, const json& body, int status = 200) {
  response.status = status;
  response.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace),
                       "application/json");
}

void send_problem(httplib::Response& response, const std::string& message, int status) {
  send_json(response, {{"ok", false}, {"problem", {{"message", message}}}}, status);
}

// The request's body, read as it comes and refused (413, and the connection closes) as soon as
// it passes kMaxRequestBytes; nullopt once the answer is set.
std::optional<std::string> read_body(const httplib::ContentReader& reader,
                                     httplib::Response& response) {
  std::string body;
  bool too_long = false;
  const bool read = reader([&](const char* data, std::size_t size) {
    too_long = size > kMaxRequestBytes - body.size();
    if (!too_long) body.append(data, size);
    return !too_long;
  });
  if (read) return body;
  BoundedHttpServer::close_after(response);
  if (too_long || response.status == 413) {
    send_problem(response, "studio: a request body is at most 8 MB", 413);
  } else {
    send_problem(response, "studio: the request's body could not be read", 400);
  }
  return std::nullopt;
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

// A request the routes never see, answered here before its body is read (the connection closes
// after the answer): a path that is not strictly percent-encoded UTF-8 text (request_path.hpp)
// 404; a method other than GET, HEAD or POST 405; a body declared longer than kMaxRequestBytes
// 413; a multipart form 415 (the API takes text). A GET or HEAD with a body is served, and its
// connection closes, its body unread.
bool refused_before_routing(const httplib::Request& request, httplib::Response& response) {
  int status = 0;
  std::string message;
  if (!request_path(request.target)) {
    status = 404;
    message = "studio: no such page";
  } else if (request.method != "GET" && request.method != "HEAD" && request.method != "POST") {
    status = 405;
    message = "studio: " + request.method + " is not a method of the studio";
  } else if (request.has_header("Content-Length") &&
             request.get_header_value<std::uint64_t>("Content-Length") > kMaxRequestBytes) {
    status = 413;
    message = "studio: a request body is at most 8 MB";
  } else if (request.is_multipart_form_data()) {
    status = 415;
    message = "studio: the API takes text, not a multipart form";
  }
  const bool has_body = request.has_header("Transfer-Encoding") ||
                        request.get_header_value<std::uint64_t>("Content-Length") > 0;
  if (status != 0 || (request.method != "POST" && has_body)) {
    BoundedHttpServer::close_after(response);
  }
  if (status == 0) return false;
  send_problem(response, message, status);
  return true;
}

}  // namespace

struct StudioServer::State {
  StudioOptions options;
  std::filesystem::path folder;  // the scenario's folder (canonical)
  BoundedHttpServer server;
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

  // A POST route: `handler` gets the request's body (read_body).
  void post(const std::string& pattern,
            std::function<void(const std::string& body, httplib::Response&)> handler) {
    server.Post(pattern,
                [handler = std::move(handler)](const httplib::Request&, httplib::Response& response,
                                               const httplib::ContentReader& reader) {
                  if (const auto body = read_body(reader, response)) handler(*body, response);
                });
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
  post("/api/view", [this](const std::string& body, httplib::Response& response) {
    auto loaded = load(body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    send_json(response, {{"ok", true}, {"view", scene_view(std::get<Simulation>(loaded))}});
  });
  // WGS-84 points as east/north metres in the local frame of `origin` (a rectangle drawn on the
  // map becomes a forest's area or a fog box, keys that take metres).
  post("/api/enu", [](const std::string& text, httplib::Response& response) {
    try {
      const json body = json::parse(text);
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
  post("/api/save", [this](const std::string& body, httplib::Response& response) {
    auto loaded = load(body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    const std::lock_guard lock(save_mutex);
    AtomicOutputFile file(options.scenario_file);
    file.write(body);
    file.commit();
    send_json(response, {{"ok", true}, {"saved", options.scenario_file.filename().string()}});
  });
  post("/api/fly", [this](const std::string& body, httplib::Response& response) {
    auto loaded = load(body);
    if (auto* problem = std::get_if<json>(&loaded)) {
      send_json(response, {{"ok", false}, {"problem", *problem}});
      return;
    }
    if (!job.start(body, options.scenario_file, options.out)) {
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
  post("/api/cancel", [this](const std::string&, httplib::Response& response) {
    job.cancel();
    send_json(response, job.status());
  });
  // The output folder's files (the report page and what it links), confined to the folder.
  server.Get(R"(/out/(.+))", [this](const httplib::Request& request, httplib::Response& response) {
    const std::string name = request.matches[1].str();
    try {
      serve_file(response, fs::weakly_canonical(options.out), name,
                 std::string(content_type_of(name)));
      response.set_header("Content-Security-Policy", kReportSecurityPolicy);
    } catch (const std::exception&) {
      send_problem(response, "studio: out/" + name + ": no such file in the output folder", 404);
    }
  });
  // A POST to no route above: refused before its body is read.
  server.Post(".*", [](const httplib::Request&, httplib::Response& response,
                       const httplib::ContentReader&) {
    BoundedHttpServer::close_after(response);
    send_problem(response, "studio: no such page", 404);
  });
}

StudioServer::StudioServer(StudioOptions options) : state_(std::make_unique<State>()) {
  State& state = *state_;
  if (options.token.empty()) options.token = new_session_token();
  options.scenario_file = std::filesystem::absolute(options.scenario_file);
  options.out = std::filesystem::absolute(options.out);
  state.folder = std::filesystem::weakly_canonical(options.scenario_file.parent_path());
  check_output_folder(std::filesystem::weakly_canonical(options.out), options.scenario_file);
  state.options = std::move(options);
  BoundedHttpServer& server = state.server;
  server.set_payload_max_length(kMaxRequestBytes);
  server.set_pre_routing_handler([&state](const httplib::Request& request,
                                          httplib::Response& response) {
    RequestFacts facts;
    facts.host = header(request, "Host");
    facts.origin = header(request, "Origin");
    facts.token_header = header(request, "X-Owsim-Token");
    facts.cookie = header(request, "Cookie");
    if (request.has_param("token")) facts.token_query = request.get_param_value("token");
    const Verdict verdict = check_request(facts, state.port, state.options.token);
    if (verdict != Verdict::allowed) {
      BoundedHttpServer::close_after(response);
      response.status = verdict == Verdict::no_token ? 401 : 403;
      response.set_content(std::string(verdict_text(verdict)) + "\n", "text/plain");
      return httplib::Server::HandlerResponse::Handled;
    }
    return refused_before_routing(request, response) ? httplib::Server::HandlerResponse::Handled
                                                     : httplib::Server::HandlerResponse::Unhandled;
  });
  // owsim's own errors are one line meant for the user; anything else is not shown.
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
        std::string message = "studio: an unexpected error";
        try {
          std::rethrow_exception(std::move(error));
        } catch (const Error& owsim_error) {
          message = owsim_error.what();
        } catch (...) {
        }
        BoundedHttpServer::close_after(response);
        send_problem(response, message, 500);
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
  server.widen_listen_queue();
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
