// Protects `owsim studio`'s server (studio/): who may talk to it (request_guard.hpp, Jupyter's
// model: token, Host, Origin), where it reads and writes (the scenario's folder and the output
// folder only), that it listens on the loopback address only (read back from the kernel's socket
// table, /proc/net/tcp), that a bad scenario comes back as the loader's line with its key and the
// server keeps serving, and one run at a time.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "owsim/simulation.hpp"
#include "studio/flight_job.hpp"
#include "studio/loader_message.hpp"
#include "studio/new_scenario.hpp"
#include "studio/request_guard.hpp"
#include "studio/studio_server.hpp"

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(RequestGuard, TokenHostAndOriginAsJupyterChecksThem) {
  const std::string token = new_session_token();
  EXPECT_EQ(token.size(), 32u);
  EXPECT_NE(token, new_session_token());
  RequestFacts request;
  request.host = "127.0.0.1:8123";
  EXPECT_EQ(check_request(request, 8123, token), Verdict::no_token);
  request.token_query = token;
  EXPECT_EQ(check_request(request, 8123, token), Verdict::allowed);
  request.token_query = token.substr(0, 31) + "x";
  EXPECT_EQ(check_request(request, 8123, token), Verdict::no_token);
  request.token_query.reset();
  request.token_header = token;
  EXPECT_EQ(check_request(request, 8123, token), Verdict::allowed);
  request.token_header.reset();
  request.cookie = "theme=dark; owsim_token=" + token + "; other=1";
  EXPECT_EQ(check_request(request, 8123, token), Verdict::allowed);
  request.cookie = "owsim_token_x=" + token;
  EXPECT_EQ(check_request(request, 8123, token), Verdict::no_token);
  request.cookie = "owsim_token=" + token;
  // DNS rebinding: a name that resolves to 127.0.0.1 still names another site.
  for (const char* host : {"evil.example:8123", "127.0.0.1:8124", "127.0.0.1", "0.0.0.0:8123",
                           "127.0.0.1:8123.evil.example"}) {
    request.host = host;
    EXPECT_EQ(check_request(request, 8123, token), Verdict::bad_host) << host;
  }
  request.host.reset();
  EXPECT_EQ(check_request(request, 8123, token), Verdict::bad_host);
  for (const char* host : {"127.0.0.1:8123", "localhost:8123", "[::1]:8123"}) {
    request.host = host;
    EXPECT_EQ(check_request(request, 8123, token), Verdict::allowed) << host;
  }
  // A cross-site request carries its page's Origin, which is refused even with the cookie.
  for (const char* origin : {"http://evil.example", "null", "http://127.0.0.1:9999",
                             "https://127.0.0.1:8123", "http://localhost:8123.evil.example"}) {
    request.origin = origin;
    EXPECT_EQ(check_request(request, 8123, token), Verdict::bad_origin) << origin;
  }
  request.origin = "http://localhost:8123";
  EXPECT_EQ(check_request(request, 8123, token), Verdict::allowed);
}

TEST(LoaderMessage, TheLineAndKeyComeApartForTheFormField) {
  const json parsed = loader_message(
      "/tmp/a b/s.yaml:9: scene.spans[0].conductor.diameter_mm: must be in [1, 200] mm, got -3",
      "/tmp/a b/s.yaml");
  EXPECT_EQ(parsed["line"], 9);
  EXPECT_EQ(parsed["key"], "scene.spans[0].conductor.diameter_mm");
  EXPECT_EQ(parsed["problem"], "must be in [1, 200] mm, got -3");
  const json no_key =
      loader_message("/tmp/s.yaml:1: origin: required, but missing from the file", "/tmp/s.yaml");
  EXPECT_EQ(no_key["key"], "origin");
  const json other = loader_message("flight.log:12: GPS time going back", "/tmp/s.yaml");
  EXPECT_FALSE(other.contains("key"));
  EXPECT_FALSE(other.contains("line"));
  EXPECT_EQ(other["message"], "flight.log:12: GPS time going back");
}

class StudioServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("owsim_studio_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "scenario");
    fs::copy_file(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml",
                  root_ / "scenario/single_span.yaml");
    StudioOptions options;
    options.scenario_file = root_ / "scenario/single_span.yaml";
    options.out = root_ / "out";
    fs::create_directories(options.out);
    server_ = std::make_unique<StudioServer>(options);
    serving_ = std::thread([this] { server_->serve(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->port());
    for (int attempt = 0; attempt < 100 && !client_->Get("/"); ++attempt) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  void TearDown() override {
    server_->stop();
    serving_.join();
    fs::remove_all(root_);
  }
  httplib::Headers with_token() const { return {{"X-Owsim-Token", server_->token()}}; }

  fs::path root_;
  std::unique_ptr<StudioServer> server_;
  std::thread serving_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(StudioServerTest, RequestsWithoutTheTokenOrFromAnotherSiteAreRefused) {
  EXPECT_EQ(client_->Get("/api/session")->status, 401);
  EXPECT_EQ(client_->Get("/")->status, 401);
  EXPECT_EQ(client_->Post("/api/save", "name: x\n", "text/plain")->status, 401);
  EXPECT_EQ(client_->Get("/api/session", with_token())->status, 200);
  EXPECT_EQ(client_->Get("/api/session?token=" + server_->token())->status, 200);
  httplib::Headers rebound = with_token();
  rebound.emplace("Host", "attacker.example:" + std::to_string(server_->port()));
  EXPECT_EQ(client_->Get("/api/session", rebound)->status, 403);
  httplib::Headers cross_site = with_token();
  cross_site.emplace("Origin", "http://attacker.example");
  EXPECT_EQ(client_->Post("/api/save", cross_site, "name: x\n", "text/plain")->status, 403);
  // Nothing was written by the refused Save.
  EXPECT_EQ(read_text(root_ / "scenario/single_span.yaml"),
            read_text(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml"));
  // The page sets the token as a cookie its own requests carry.
  const auto page = client_->Get("/?token=" + server_->token());
  ASSERT_EQ(page->status, 200);
  EXPECT_NE(page->get_header_value("Set-Cookie").find("owsim_token=" + server_->token()),
            std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'self'"),
            std::string::npos);
  EXPECT_EQ(client_->Get("/api/session", {{"Cookie", "owsim_token=" + server_->token()}})->status,
            200);
}

TEST_F(StudioServerTest, ItListensOnTheLoopbackAddressOnly) {
  // /proc/net/tcp: local address as hex IP:port, state 0A = LISTEN; 127.0.0.1 is 0100007F.
  std::ifstream table("/proc/net/tcp");
  std::string line;
  char port_hex[8];
  std::snprintf(port_hex, sizeof port_hex, "%04X", server_->port());
  int listening = 0;
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    std::string slot, local, remote, state;
    fields >> slot >> local >> remote >> state;
    if (state == "0A" && local.ends_with(std::string(":") + port_hex)) {
      ++listening;
      EXPECT_EQ(local.substr(0, 8), "0100007F") << line;
    }
  }
  EXPECT_EQ(listening, 1);
  // And nothing on IPv6 (no [::] socket on that port).
  std::ifstream table6("/proc/net/tcp6");
  while (std::getline(table6, line)) {
    EXPECT_EQ(line.find(std::string(":") + port_hex + " 00000000000000000000000000000000:0000 0A"),
              std::string::npos)
        << line;
  }
}

TEST_F(StudioServerTest, FilesOutsideTheOutputFolderAreNeverServed) {
  std::ofstream(root_ / "out/report.html") << "<p>report</p>";
  std::ofstream(root_ / "secret.txt") << "confidential content";
  fs::create_symlink(root_ / "secret.txt", root_ / "out/link.txt");
  fs::create_symlink("/etc/hostname", root_ / "out/hostname");
  const auto report = client_->Get("/out/report.html", with_token());
  ASSERT_EQ(report->status, 200);
  EXPECT_EQ(report->body, "<p>report</p>");
  for (const char* path : {"/out/../secret.txt", "/out/%2e%2e/secret.txt", "/out/link.txt",
                           "/out/hostname", "/out//etc/passwd", "/out/..%2f..%2fetc/passwd",
                           "/out/../scenario/single_span.yaml", "/out/missing.html"}) {
    const auto response = client_->Get(path, with_token());
    ASSERT_TRUE(response) << path;
    EXPECT_NE(response->status, 200) << path;
    EXPECT_EQ(response->body.find("confidential"), std::string::npos) << path;
  }
}

TEST_F(StudioServerTest, TheModelFilesOfferedAreTheScenarioFoldersOwn) {
  fs::create_directories(root_ / "scenario/models/deeper");
  std::ofstream(root_ / "scenario/models/barn.obj") << "v 0 0 0\n";
  std::ofstream(root_ / "scenario/models/deeper/Tower.PLY") << "ply\n";
  std::ofstream(root_ / "scenario/notes.txt") << "not a model";
  std::ofstream(root_ / "outside.obj") << "v 0 0 0\n";
  fs::create_symlink(root_ / "outside.obj", root_ / "scenario/linked.obj");
  fs::create_symlink(root_, root_ / "scenario/models/up");  // a loop out of the folder
  const json answer = json::parse(client_->Get("/api/models", with_token())->body);
  EXPECT_EQ(answer["files"], json::array({"models/barn.obj", "models/deeper/Tower.PLY"}));
}

TEST_F(StudioServerTest, ABadScenarioIsTheLoadersLineWithItsKeyAndTheServerKeepsServing) {
  std::string yaml = read_text(root_ / "scenario/single_span.yaml");
  const std::string good = yaml;
  const std::size_t at = yaml.find("diameter_mm: 20");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, 15, "diameter_mm: -3");
  const auto bad = client_->Post("/api/view", with_token(), yaml, "text/plain");
  ASSERT_EQ(bad->status, 200);
  const json answer = json::parse(bad->body);
  EXPECT_FALSE(answer["ok"]);
  EXPECT_EQ(answer["problem"]["key"], "scene.spans[0].conductor.diameter_mm");
  EXPECT_TRUE(answer["problem"].contains("line"));
  // Save refuses it and leaves the file as it was.
  EXPECT_FALSE(
      json::parse(client_->Post("/api/save", with_token(), yaml, "text/plain")->body)["ok"]);
  EXPECT_EQ(read_text(root_ / "scenario/single_span.yaml"), good);
  for (const std::string& garbage : {std::string("\x01\x02: ["), std::string(100000, '{'),
                                     std::string("origin: {lat: 1e999}")}) {
    const auto response = client_->Post("/api/view", with_token(), garbage, "text/plain");
    ASSERT_TRUE(response);
    EXPECT_FALSE(json::parse(response->body)["ok"]);
  }
  const auto view = client_->Post("/api/view", with_token(), good, "text/plain");
  ASSERT_EQ(view->status, 200);
  const json shown = json::parse(view->body);
  ASSERT_TRUE(shown["ok"]);
  EXPECT_GT(shown["view"]["track"]["t"].size(), 10u);
  EXPECT_FALSE(shown["view"]["objects"].empty());
  // Save of a good scenario writes exactly the text sent.
  const std::string edited = good + "# edited\n";
  EXPECT_TRUE(
      json::parse(client_->Post("/api/save", with_token(), edited, "text/plain")->body)["ok"]);
  EXPECT_EQ(read_text(root_ / "scenario/single_span.yaml"), edited);
}

TEST(NewScenario, APlannedFlightAndARecordedOneLoadAsWritten) {
  const Simulation planned = Simulation::from_yaml(new_planned_scenario_yaml("studio"),
                                                   fs::temp_directory_path() / "studio.yaml");
  EXPECT_EQ(planned.frame_count(), 30);  // the 10 s selected of the 60 s leg
  EXPECT_EQ(trajectory_format_of("a/flight.log"), "ardupilot");
  EXPECT_EQ(trajectory_format_of("flight.csv"), "csv");
  EXPECT_EQ(trajectory_format_of("flight.out"), "sbet");
  EXPECT_EQ(trajectory_format_of("flight.txt"), "hellsim");
}

TEST(FlightJob, OneRunAtATimeAndACancelEndsIt) {
  const fs::path root =
      fs::temp_directory_path() / ("owsim_flight_job_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const std::string yaml = read_text(fs::path(OWSIM_SOURCE_DIR) / "examples/corridor.yaml");
  FlightJob job;
  ASSERT_TRUE(job.start(yaml, fs::path(OWSIM_SOURCE_DIR) / "examples/corridor.yaml", root / "a"));
  EXPECT_FALSE(job.start(yaml, fs::path(OWSIM_SOURCE_DIR) / "examples/corridor.yaml", root / "b"));
  job.cancel();
  job.wait();
  EXPECT_EQ(job.status()["state"], "cancelled");
  EXPECT_FALSE(fs::exists(root / "b"));
  EXPECT_FALSE(fs::exists(root / "a/flight.d64"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace owsim::studio
