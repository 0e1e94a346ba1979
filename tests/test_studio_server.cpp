// Protects `owsim studio`'s server (studio/): who may talk to it (request_guard.hpp, Jupyter's
// model: token, Host, Origin), where it reads and writes (the scenario's folder and the output
// folder only), that it listens on the loopback address only (read back from the kernel's socket
// table, /proc/net/tcp), that a bad scenario comes back as the loader's line with its key and the
// server keeps serving, and one run at a time. Its limits (issue 45): every request body, chunked
// or compressed too, at most 8 MB and refused as it passes that; an output file streamed, not
// held in memory; a path that is not UTF-8 text a clean 404 on every route; a flight's outputs
// replaced whole or not at all. (Its connections: test_studio_connections.cpp.)
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "loopback_socket.hpp"
#include "owsim/simulation.hpp"
#include "studio/flight_job.hpp"
#include "studio/folder_replacement.hpp"
#include "studio/loader_message.hpp"
#include "studio/new_scenario.hpp"
#include "studio/request_guard.hpp"
#include "studio/request_path.hpp"
#include "studio/studio_server.hpp"

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {
namespace {

// AddressSanitizer holds freed blocks in quarantine (256 MB by default), so the pieces a stream
// sent and freed still count toward the peak: the streaming bound is checked without it.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kFreedMemoryIsReused = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kFreedMemoryIsReused = false;
#else
constexpr bool kFreedMemoryIsReused = true;
#endif
#else
constexpr bool kFreedMemoryIsReused = true;
#endif

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every file under `folder` (relative name → bytes), links and hidden files included.
std::map<std::string, std::string> folder_contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string name = entry.path().lexically_relative(folder).generic_string();
    if (entry.is_symlink()) {
      files[name] = "link to " + fs::read_symlink(entry.path()).string();
    } else if (entry.is_regular_file()) {
      files[name] = read_text(entry.path());
    }
  }
  return files;
}

// The entries of `folder`, sorted.
std::vector<std::string> entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The process's peak resident memory (KiB, /proc/self/status VmHWM) since reset_peak_memory,
// which is false when the kernel does not let it be reset (then no peak is measured).
bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return clear.good();
}
long peak_memory_kib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.starts_with("VmHWM:")) return std::stol(line.substr(6));
  }
  return 0;
}

// Byte `offset` of the large test file: a pattern that a misplaced or repeated piece breaks.
char pattern_byte(std::size_t offset) { return static_cast<char>((offset * 2654435761u) >> 13); }

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
  std::string head(const std::string& request_line, const std::string& headers = "") const {
    return request_line + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(server_->port()) +
           "\r\nX-Owsim-Token: " + server_->token() + "\r\n" + headers + "\r\n";
  }
  // Polls /api/run until the run's state is not `running_state`s or `seconds` pass.
  json run_status_after(double seconds) const {
    json status;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    do {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      status = json::parse(client_->Get("/api/run", with_token())->body);
    } while ((status["state"] == "building" || status["state"] == "flying" ||
              status["state"] == "report") &&
             std::chrono::steady_clock::now() < deadline);
    return status;
  }

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

TEST(RequestPath, StrictPercentDecodingToUtf8TextWithoutControlCharacters) {
  EXPECT_EQ(request_path("/out/a%20b.csv?run=1&x=%ff"), "/out/a b.csv");
  EXPECT_EQ(request_path("/out/%C3%A9t%c3%a9.png"), "/out/\xC3\xA9t\xC3\xA9.png");
  EXPECT_EQ(request_path("/out/%2e%2e/x"), "/out/../x");  // confinement is the route's work
  EXPECT_EQ(request_path("/"), "/");
  for (const char* target :
       {"/out/%c0%ae%c0%ae/x", "/out/%ff", "/out/%e0%80%ae", "/out/%ed%a0%80", "/out/%f4%90%80%80",
        "/out/%c3", "/out/%zz", "/out/%4", "/out/%", "/out/%u002e", "/out/a%00b", "/out/%0a",
        "/out/%7f", "/out/\xc0\xae", "/out/a\tb"}) {
    EXPECT_FALSE(request_path(target)) << target;
  }
}

TEST_F(StudioServerTest, APathThatIsNotUtf8TextIsACleanNotFoundOnEveryRoute) {
  std::ofstream(root_ / "out/report.html") << "<p>report</p>";
  client_->set_url_encode(false);
  for (const std::string bad : {"%c0%ae%c0%ae/report.html", "%ff", "%e0%80%ae", "%ed%a0%80", "%zz",
                                "%u002e%u002e/report.html", "report.html%00", "%0a"}) {
    for (const std::string route : {"/out/", "/api/session", "/api/models", "/", "/studio.js"}) {
      const auto response = client_->Get(route + bad, with_token());
      ASSERT_TRUE(response) << route << bad;
      EXPECT_EQ(response->status, 404) << route << bad;
      const json answer = json::parse(response->body);
      EXPECT_EQ(answer["problem"]["message"], "studio: no such page") << route << bad;
    }
    for (const std::string route : {"/api/view", "/api/save", "/api/fly"}) {
      const auto response = client_->Post(route + bad, with_token(), "name: x\n", "text/plain");
      ASSERT_TRUE(response) << route << bad;
      EXPECT_EQ(response->status, 404) << route << bad;
    }
  }
  // A name that is UTF-8 but no file: the route's own 404, naming what was asked, no more.
  const auto missing = client_->Get("/out/%c3%a9t%c3%a9.html", with_token());
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(json::parse(missing->body)["problem"]["message"],
            "studio: out/\xC3\xA9t\xC3\xA9.html: no such file in the output folder");
  EXPECT_EQ(client_->Get("/out/report.html", with_token())->body, "<p>report</p>");
  EXPECT_EQ(read_text(root_ / "scenario/single_span.yaml"),
            read_text(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml"));
}

TEST_F(StudioServerTest, AChunkedBodyIsRefusedAsItPassesTheLimitNotReadWhole) {
  const bool measured = reset_peak_memory();
  const long peak_before = peak_memory_kib();
  test::LoopbackSocket connection(server_->port());
  ASSERT_TRUE(connection.send(
      head("POST /api/view", "Content-Type: text/plain\r\nTransfer-Encoding: chunked\r\n")));
  const std::size_t piece = 64u << 10;
  const std::string chunk = "10000\r\n" + std::string(piece, 'x') + "\r\n";
  const std::size_t body = 64u << 20;
  std::size_t sent = 0;
  while (sent < body && !connection.readable(std::chrono::milliseconds(0)) &&
         connection.send(chunk)) {
    sent += piece;
  }
  const std::string answer = connection.read_all(std::chrono::seconds(10));
  EXPECT_TRUE(answer.starts_with("HTTP/1.1 413")) << answer.substr(0, 200);
  EXPECT_NE(answer.find("a request body is at most 8 MB"), std::string::npos);
  EXPECT_LT(sent, body / 2);  // answered near the limit, not at the end of the body
  if (measured) EXPECT_LT(peak_memory_kib() - peak_before, 32 << 10);  // KiB: not the 64 MB
  // The server keeps serving, and a chunked body within the limit is read as any other.
  const std::string yaml = read_text(root_ / "scenario/single_span.yaml");
  const auto view = client_->Post(
      "/api/view", with_token(),
      [&](std::size_t offset, httplib::DataSink& sink) {
        if (offset < yaml.size())
          sink.write(yaml.data() + offset, std::min<std::size_t>(100, yaml.size() - offset));
        if (offset + 100 >= yaml.size()) sink.done();
        return true;
      },
      "text/plain");
  ASSERT_TRUE(view);
  EXPECT_EQ(view->status, 200);
  EXPECT_TRUE(json::parse(view->body)["ok"]);
}

TEST_F(StudioServerTest, EveryBodyIsBoundedHoweverItComes) {
  // Declared too long: refused before a byte of it is read.
  test::LoopbackSocket declared(server_->port());
  ASSERT_TRUE(declared.send(head("POST /api/save", "Content-Length: 300000000\r\n")));
  const std::string refused = declared.read_all(std::chrono::seconds(5));
  EXPECT_TRUE(refused.starts_with("HTTP/1.1 413")) << refused.substr(0, 200);
  // gzip: bounded by what it expands to (16 MB of spaces are some 16 kB compressed).
  httplib::Client compressing("127.0.0.1", server_->port());
  compressing.set_compress(true);
  const auto bomb =
      compressing.Post("/api/save", with_token(), std::string(16u << 20, ' '), "text/plain");
  ASSERT_TRUE(bomb);
  EXPECT_EQ(bomb->status, 413);
  // Methods the studio has no route for, and a POST to no route, are refused unread.
  EXPECT_EQ(client_->Put("/api/save", with_token(), "name: x\n", "text/plain")->status, 405);
  EXPECT_EQ(client_->Delete("/api/save", with_token())->status, 405);
  EXPECT_EQ(client_->Post("/api/nothing", with_token(), "name: x\n", "text/plain")->status, 404);
  EXPECT_EQ(read_text(root_ / "scenario/single_span.yaml"),
            read_text(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml"));
  EXPECT_EQ(client_->Get("/api/session", with_token())->status, 200);
}

TEST_F(StudioServerTest, AnOutputFileIsStreamedByteForByteNotHeldInMemory) {
  const std::size_t size = (48u << 20) + 12345;
  {
    std::ofstream file(root_ / "out/points.ply", std::ios::binary);
    std::string piece(1u << 20, '\0');
    for (std::size_t offset = 0; offset < size; offset += piece.size()) {
      const std::size_t length = std::min(piece.size(), size - offset);
      for (std::size_t k = 0; k < length; ++k) piece[k] = pattern_byte(offset + k);
      file.write(piece.data(), static_cast<std::streamsize>(length));
    }
  }
  const bool measured = reset_peak_memory();
  const long peak_before = peak_memory_kib();
  std::size_t received = 0;
  std::size_t first_wrong = std::string::npos;
  const auto response =
      client_->Get("/out/points.ply", with_token(), [&](const char* data, std::size_t length) {
        for (std::size_t k = 0; k < length; ++k) {
          if (data[k] != pattern_byte(received + k) && first_wrong == std::string::npos) {
            first_wrong = received + k;
          }
        }
        received += length;
        return true;
      });
  ASSERT_TRUE(response);
  EXPECT_EQ(response->status, 200);
  EXPECT_EQ(received, size);
  EXPECT_EQ(first_wrong, std::string::npos);
  EXPECT_EQ(response->get_header_value("Content-Length"), std::to_string(size));
  if (measured && kFreedMemoryIsReused) {
    EXPECT_LT(peak_memory_kib() - peak_before, 16 << 10);  // KiB: not 2 × 48 MB
  }
  // An empty file, and HEAD, which sends the length and no body.
  std::ofstream(root_ / "out/empty.csv");
  const auto empty = client_->Get("/out/empty.csv", with_token());
  EXPECT_EQ(empty->status, 200);
  EXPECT_EQ(empty->body, "");
  const auto head_only = client_->Head("/out/points.ply", with_token());
  EXPECT_EQ(head_only->status, 200);
  EXPECT_EQ(head_only->get_header_value("Content-Length"), std::to_string(size));
  EXPECT_TRUE(head_only->body.empty());
}

TEST_F(StudioServerTest, ACancelledFlyLeavesThePreviousFlightsFilesExactlyAsTheyWere) {
  const std::string yaml = read_text(root_ / "scenario/single_span.yaml");
  ASSERT_TRUE(json::parse(client_->Post("/api/fly", with_token(), yaml, "text/plain")->body)["ok"]);
  ASSERT_EQ(run_status_after(300)["state"], "done");
  const auto first = folder_contents(root_ / "out");
  EXPECT_TRUE(first.contains("flight.d64"));
  EXPECT_TRUE(first.contains("report.html"));
  EXPECT_TRUE(first.contains("quicklook/frame_000010.png"));
  EXPECT_FALSE(first.contains("quicklook/frame_000050.png"));
  // A longer flight (a quick-look frame every 10 frames), cancelled once it has written some.
  std::string longer = yaml;
  longer.replace(longer.find("{e: 200, n: 0, u: 60}"), 21, "{e: 6000, n: 0, u: 60}");
  longer.replace(longer.find("duration_s: 15"), 14, "duration_s: 140");
  ASSERT_TRUE(
      json::parse(client_->Post("/api/fly", with_token(), longer, "text/plain")->body)["ok"]);
  json status;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    status = json::parse(client_->Get("/api/run", with_token())->body);
  } while (status["frames_done"].get<int>() < 60 && status["state"] != "failed" &&
           std::chrono::steady_clock::now() < deadline);
  ASSERT_EQ(status["state"], "flying");
  client_->Post("/api/cancel", with_token(), "", "text/plain");
  ASSERT_EQ(run_status_after(60)["state"], "cancelled");
  EXPECT_EQ(folder_contents(root_ / "out"), first);
  // Nothing of the cancelled flight is left beside it.
  EXPECT_EQ(entries(root_), (std::vector<std::string>{"out", "scenario"}));
}

TEST_F(StudioServerTest, FlyRefusesAnOutputFolderHoldingFilesThatAreNotAFlights) {
  std::ofstream(root_ / "out/notes.txt") << "mine";
  const std::string yaml = read_text(root_ / "scenario/single_span.yaml");
  ASSERT_TRUE(json::parse(client_->Post("/api/fly", with_token(), yaml, "text/plain")->body)["ok"]);
  const json status = run_status_after(300);
  EXPECT_EQ(status["state"], "failed");
  EXPECT_NE(status["error"].get<std::string>().find(
                "holds files that are not a flight's (no summary.json); Fly replaces its output "
                "folder whole: choose another --out"),
            std::string::npos)
      << status["error"];
  EXPECT_EQ(folder_contents(root_ / "out"),
            (std::map<std::string, std::string>{{"notes.txt", "mine"}}));
  EXPECT_EQ(entries(root_), (std::vector<std::string>{"out", "scenario"}));
}

TEST(FolderReplacement, TheNewFolderTakesTheOldOnesPlaceWholeOrNotAtAll) {
  const fs::path root =
      fs::temp_directory_path() / ("owsim_folder_replacement_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path folder = root / "out/flight";
  {
    // Into a folder that does not exist yet (nor its parent).
    FolderReplacement replacement(folder);
    EXPECT_EQ(replacement.path().parent_path(), folder.parent_path());
    EXPECT_TRUE(replacement.path().filename().string().starts_with(".flight."));
    std::ofstream(replacement.path() / "a.txt") << "first";
    replacement.commit();
  }
  EXPECT_EQ(folder_contents(folder), (std::map<std::string, std::string>{{"a.txt", "first"}}));
  {
    // Not committed: the previous folder stays as it was, and the new one goes.
    FolderReplacement replacement(folder);
    std::ofstream(replacement.path() / "b.txt") << "second";
    fs::create_directories(replacement.path() / "quicklook");
    std::ofstream(replacement.path() / "quicklook/frame_000000.png") << "png";
  }
  EXPECT_EQ(folder_contents(folder), (std::map<std::string, std::string>{{"a.txt", "first"}}));
  EXPECT_EQ(entries(root / "out"), (std::vector<std::string>{"flight"}));
  {
    FolderReplacement replacement(folder);
    std::ofstream(replacement.path() / "b.txt") << "second";
    replacement.commit();
  }
  EXPECT_EQ(folder_contents(folder), (std::map<std::string, std::string>{{"b.txt", "second"}}));
  EXPECT_EQ(entries(root / "out"), (std::vector<std::string>{"flight"}));
  fs::remove_all(root);
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
