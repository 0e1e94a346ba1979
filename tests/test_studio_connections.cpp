// Protects `owsim studio` from being starved by other local processes (issue 45): the user's
// requests are answered within a second while 200 idle and 10 slow connections are open; a slow
// request head is cut off at its deadline, an idle connection at its own; past the connection cap
// the longest-waiting connection is closed; an oversized head is refused. And the thread queue
// underneath (studio/growing_task_queue.hpp) grows on demand and lets idle threads end.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "loopback_socket.hpp"
#include "studio/studio_server.hpp"

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

#include "studio/bounded_http_server.hpp"
#include "studio/growing_task_queue.hpp"

namespace owsim::studio {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using test::LoopbackSocket;

TEST(GrowingTaskQueue, AThreadForEveryTaskThatWouldWaitAndIdleThreadsEnd) {
  GrowingTaskQueue queue(12, milliseconds(200));
  std::atomic<int> started{0};
  std::atomic<bool> release{false};
  // Ten tasks that hold their thread: all run at once, none waits for another.
  for (int k = 0; k < 10; ++k) {
    queue.enqueue([&] {
      ++started;
      while (!release) std::this_thread::sleep_for(milliseconds(5));
    });
  }
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (started < 10 && Clock::now() < deadline) std::this_thread::sleep_for(milliseconds(5));
  EXPECT_EQ(started, 10);
  EXPECT_EQ(queue.threads(), 10u);
  // Past the cap, tasks wait for a thread.
  for (int k = 0; k < 4; ++k) {
    queue.enqueue([&] {
      ++started;
      while (!release) std::this_thread::sleep_for(milliseconds(5));
    });
  }
  std::this_thread::sleep_for(milliseconds(100));
  EXPECT_EQ(started, 12);
  EXPECT_EQ(queue.threads(), 12u);
  release = true;
  while (started < 14 && Clock::now() < deadline) std::this_thread::sleep_for(milliseconds(5));
  EXPECT_EQ(started, 14);
  // Idle for 200 ms, the threads end.
  while (queue.threads() > 0 && Clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(20));
  }
  EXPECT_EQ(queue.threads(), 0u);
  std::atomic<bool> ran{false};
  queue.enqueue([&] { ran = true; });
  queue.shutdown();
  EXPECT_TRUE(ran);
}

class StudioConnections : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("owsim_studio_connections_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    fs::copy_file(fs::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml",
                  root_ / "single_span.yaml");
    StudioOptions options;
    options.scenario_file = root_ / "single_span.yaml";
    options.out = root_ / "out";
    server_ = std::make_unique<StudioServer>(options);
    serving_ = std::thread([this] { server_->serve(); });
    httplib::Client probe("127.0.0.1", server_->port());
    for (int attempt = 0; attempt < 100 && !probe.Get("/"); ++attempt) {
      std::this_thread::sleep_for(milliseconds(20));
    }
  }
  void TearDown() override {
    server_->stop();
    serving_.join();
    fs::remove_all(root_);
  }

  // One request of the user's, on a connection of its own (as a browser opens one when its
  // others are busy): its status, and the time it took in `took`.
  int user_request(Clock::duration& took) const {
    httplib::Client user("127.0.0.1", server_->port());
    user.set_connection_timeout(5);
    user.set_read_timeout(5);
    const Clock::time_point start = Clock::now();
    const auto response = user.Get("/api/session", {{"X-Owsim-Token", server_->token()}});
    took = Clock::now() - start;
    return response ? response->status : -1;
  }

  std::string request_head() const {
    return "GET /api/session HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(server_->port()) +
           "\r\nX-Owsim-Token: " + server_->token() + "\r\n\r\n";
  }

  fs::path root_;
  std::unique_ptr<StudioServer> server_;
  std::thread serving_;
};

TEST_F(StudioConnections, IdleAndSlowConnectionsDoNotStarveTheUsersRequests) {
  const Clock::time_point opened = Clock::now();
  std::vector<LoopbackSocket> idle;
  for (int k = 0; k < 200; ++k) idle.emplace_back(server_->port());
  // Ten connections sending a valid request's head one byte every 3 s.
  std::vector<LoopbackSocket> slow;
  for (int k = 0; k < 10; ++k) slow.emplace_back(server_->port());
  const std::string head = request_head();
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    for (std::size_t byte = 0; !done && byte < head.size(); ++byte) {
      for (LoopbackSocket& connection : slow) (void)connection.send(head.substr(byte, 1));
      for (int step = 0; step < 30 && !done; ++step) std::this_thread::sleep_for(milliseconds(100));
    }
  });
  for (int k = 0; k < 10; ++k) {
    Clock::duration took{};
    EXPECT_EQ(user_request(took), 200) << "request " << k;
    EXPECT_LT(took, std::chrono::seconds(1)) << "request " << k;
    std::this_thread::sleep_for(milliseconds(300));
  }
  // Their heads never arrive whole: each slow connection is closed once kHeadWithin has passed.
  for (LoopbackSocket& connection : slow) {
    EXPECT_TRUE(connection.closed_by_server(std::chrono::duration_cast<milliseconds>(
        opened + kHeadWithin + std::chrono::seconds(4) - Clock::now())));
  }
  const Clock::duration slow_closed_after = Clock::now() - opened;
  EXPECT_GE(slow_closed_after, kHeadWithin - std::chrono::seconds(1));
  EXPECT_LT(slow_closed_after, kHeadWithin + std::chrono::seconds(4));
  // The idle ones, which never sent a byte, were closed after kFirstByteWithin.
  int idle_open = 0;
  for (LoopbackSocket& connection : idle)
    idle_open += connection.closed_by_server(milliseconds(0)) ? 0 : 1;
  EXPECT_EQ(idle_open, 0);
  done = true;
  trickle.join();
}

TEST_F(StudioConnections, PastTheCapTheConnectionWaitingLongestIsClosed) {
  const Clock::time_point opened = Clock::now();
  std::vector<LoopbackSocket> idle;
  for (std::size_t k = 0; k < kMaxConnections + 40; ++k) idle.emplace_back(server_->port());
  for (int k = 0; k < 5; ++k) {
    Clock::duration took{};
    EXPECT_EQ(user_request(took), 200) << "request " << k;
    EXPECT_LT(took, std::chrono::seconds(1)) << "request " << k;
  }
  // Room was made by closing connections that had waited longest: 40 (and one for each of the
  // user's connections that came while the cap was reached), none of the newest.
  ASSERT_LT(Clock::now() - opened, kFirstByteWithin - std::chrono::seconds(1))
      << "too slow to tell connections closed for room from idle ones";
  std::vector<bool> closed(idle.size(), false);
  std::size_t closed_count = 0;
  const auto look = [&] {
    for (std::size_t k = 0; k < idle.size(); ++k) {
      if (!closed[k] && idle[k].closed_by_server(milliseconds(0))) {
        closed[k] = true;
        ++closed_count;
      }
    }
  };
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(1);
  for (look(); closed_count < 40 && Clock::now() < deadline; look()) {
    std::this_thread::sleep_for(milliseconds(20));
  }
  std::this_thread::sleep_for(milliseconds(200));
  look();
  EXPECT_GE(closed_count, 40u);
  EXPECT_LE(closed_count, 45u);
  for (std::size_t k = idle.size() - 40; k < idle.size(); ++k) {
    EXPECT_FALSE(closed[k]) << "connection " << k << " of " << idle.size();
  }
}

TEST_F(StudioConnections, AHeadPastItsSizeIsRefusedAndTheServerKeepsServing) {
  LoopbackSocket connection(server_->port());
  // Each header line is short; together they pass kMaxHeadBytes (httplib bounds only a line).
  std::string head = request_head();
  for (std::size_t k = 0; k * 100 < 2 * kMaxHeadBytes; ++k) {
    head.insert(head.size() - 2,
                "X-Padding-" + std::to_string(k) + ": " + std::string(80, 'a') + "\r\n");
  }
  (void)connection.send(head);
  const std::string answer = connection.read_all(std::chrono::seconds(5));
  EXPECT_TRUE(answer.empty() || answer.starts_with("HTTP/1.1 400")) << answer.substr(0, 100);
  EXPECT_TRUE(connection.closed_by_server(std::chrono::seconds(5)));
  // A head within the size is served, and a second request on its connection too.
  LoopbackSocket kept(server_->port());
  ASSERT_TRUE(kept.send(request_head() + request_head()));
  std::this_thread::sleep_for(milliseconds(500));
  const std::string both = kept.read_all(milliseconds(500));
  EXPECT_TRUE(both.starts_with("HTTP/1.1 200")) << both.substr(0, 100);
  EXPECT_NE(both.find("HTTP/1.1 200", 10), std::string::npos);
}

}  // namespace
}  // namespace owsim::studio
